"""PAB base class and a state machine whose transitions are data.

A PAB (report 4.7.4) is a class with a :class:`StateMachine` (states and
guarded transitions, printable as a table like the report's Table D.1), an
action per state (motion primitives) and a ``facts`` function that reads the
robot after each action. Each guard is an expression over those facts
(:mod:`pirate.sequencer.pabs.expr`), so the test the machine runs and the
text the table prints are one. :meth:`Pab.run` is the one loop that drives
them. Pure Python.
"""
import collections

from pirate.sequencer.pabs.expr import ALWAYS, fields

END = 'END'

#: One row of a transition table: from ``source`` to ``target`` when ``guard``
#: (an expression of :mod:`pirate.sequencer.pabs.expr`) holds.
Transition = collections.namedtuple('Transition', 'source target guard')

__all__ = ['ALWAYS', 'END', 'Ended', 'Pab', 'PabFailed', 'StateMachine', 'Transition']


#: How the last goal that ran ended: its PAB's name, the PAB state it was in,
#: the odometry then (mm), its status ('succeeded', 'preempted', 'aborted')
#: and whether it ended for want of a junction (the result's junction_missing).
Ended = collections.namedtuple('Ended', 'pab state odometry_mm status junction_missing', defaults=(False,))


class PabFailed(Exception):
    """A PAB cannot go on; the message says why (goal aborted)."""


class StateMachine(object):
    """States and guarded transitions, checked for consistency on creation.

    ``facts``: the namedtuple class the PAB's facts are; every guard must
    read only its fields (None: the guards read no facts).
    """

    def __init__(self, initial, transitions, facts=None):
        self.initial = initial
        self.transitions = tuple(transitions)
        self.facts = facts
        self.states = tuple(collections.OrderedDict.fromkeys(
            [initial] + [t.source for t in self.transitions] + [t.target for t in self.transitions]))
        self.assert_consistent()
        self._check_fields()

    def _check_fields(self):
        """Every guard reads fields the facts have."""
        known = set(self.facts._fields) if self.facts is not None else set()
        for t in self.transitions:
            unknown = fields(t.guard) - known
            if unknown:
                raise ValueError('guard of %s -> %s reads %s, which the facts do not have'
                                 % (t.source, t.target, ', '.join(sorted(unknown))))

    def assert_consistent(self):
        """Every state but END has an exit and is reachable from the start."""
        sources = {t.source for t in self.transitions}
        for state in self.states:
            if state != END and state not in sources:
                raise ValueError('state %s has no transition out' % state)
        reached, frontier = {self.initial}, [self.initial]
        while frontier:
            state = frontier.pop()
            for t in self.transitions:
                if t.source == state and t.target not in reached:
                    reached.add(t.target)
                    frontier.append(t.target)
        unreachable = set(self.states) - reached
        if unreachable:
            raise ValueError('states unreachable from %s: %s' % (self.initial, sorted(unreachable)))

    def exits(self, state):
        """Transitions out of ``state``."""
        return [t for t in self.transitions if t.source == state]

    def next(self, state, facts):
        """The one target whose guard holds; PabFailed if none or several."""
        fired = [t for t in self.exits(state) if t.guard.test(facts)]
        if len(fired) != 1:
            raise PabFailed('%s: %s transition for %s' % (
                state, 'no' if not fired else 'more than one', _describe(facts)))
        return fired[0].target

    def table(self):
        """The transitions as a text table (state, next state, guard)."""
        rows = [('state', 'next state', 'guard')] + [
            (t.source, t.target, t.guard.text) for t in self.transitions]
        widths = [max(len(r[i]) for r in rows) for i in range(3)]
        return '\n'.join('  '.join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows)


def _describe(facts):
    if hasattr(facts, '_asdict'):
        return ', '.join('%s=%s' % kv for kv in facts._asdict().items())
    return repr(facts)


class Pab(object):
    """Base of every PAB: subclasses set ``name``, ``machine``, ``actions``."""

    name = 'PAB'
    machine = None
    #: True when the PAB needs the robot clamped to start (Fig 4.2: Drive).
    requires_clamped = False
    #: How the last goal that ran ended (:meth:`follows`).
    after = None

    @classmethod
    def for_goal(cls, goal):
        """The PAB instance that runs ``goal`` (a PAB serving several goals reads it here)."""
        return cls()

    @classmethod
    def takes(cls, name, option, rear_first=False):
        """False when this PAB refuses goal ``name`` with ``option`` whatever the
        robot's state (a direction it does not take yet); codes of Pirate.action.
        ``rear_first``: the goal searches backwards (a negative distance)."""
        return True

    def check(self, goal, view, guards):
        """Reason the goal cannot run, or None (called before accepting)."""
        return None

    def carry_on(self, record):
        """Take what the last run of this same goal left (:meth:`unfinished`),
        before :meth:`check` and :meth:`run`. Most PABs start from what the
        robot senses alone and keep nothing."""

    def follows(self, ended):
        """How the last goal that ran ended (:data:`Ended`, or None), before
        :meth:`check` and :meth:`run`: the robot's own recent history, for a
        PAB whose start depends on it (Home after a turn stopped in a corner)."""
        self.after = ended

    def unfinished(self):
        """What a run that did not succeed leaves for the same goal re-sent
        (the server keeps it until another goal runs), or None: a namedtuple
        of plain values, which a restarted manager keeps (:meth:`record_from`)."""
        return None

    @classmethod
    def record_from(cls, data):
        """The record :meth:`unfinished` returns, from its fields in ``data``
        (a dict, as a restarted manager kept it); ValueError when this PAB
        keeps no record or ``data`` is not one."""
        raise ValueError('%s keeps no record' % cls.__name__)

    def facts(self, ctx):
        """What the guards of the transitions look at, read after an action."""
        return None

    def actions(self):
        """Map state -> callable(ctx)."""
        raise NotImplementedError

    def run(self, ctx):
        """Drive the state machine to END; return a message for the result."""
        actions = self.actions()
        state = self.machine.initial
        limit = ctx.guards.max_primitives
        for _ in range(limit):
            ctx.feed.check()
            ctx.report(state)
            actions[state](ctx)
            state = self.machine.next(state, self.facts(ctx))
            if state == END:
                ctx.report(END)
                return self.summary(ctx)
        raise PabFailed('%s did not finish within %d states' % (self.name, limit))

    def summary(self, ctx):
        """Result message on success."""
        return '%s done' % self.name
