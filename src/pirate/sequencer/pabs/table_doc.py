"""A PAB's transition table as Markdown, from the machine that runs.

:func:`markdown` prints the table as the report's Table D.1 does (state,
next state, guard; a state named once above its transitions), then the
named conditions its guards use, spelled out, and the facts they read with
what each means: all from the guards' expressions
(:mod:`pirate.sequencer.pabs.expr`), so the printed table cannot disagree
with the code. ``make docs`` writes it into doc/sequencer.md
(:mod:`pirate.docs`). Pure.
"""
from pirate.sequencer.pabs.expr import Equals, definitions, facts_read


def markdown(machine):
    """``machine`` (a :class:`~pirate.sequencer.pabs.base.StateMachine`) as Markdown lines joined by newlines."""
    guards = [t.guard for t in machine.transitions]
    lines = _table(machine) + _named(guards) + _facts(guards, machine.facts)
    return '\n'.join(lines)


def _table(machine):
    lines = ['| state | next state | guard |', '|---|---|---|']
    previous = None
    for t in machine.transitions:
        lines.append('| %s | %s | %s |' % (t.source if t.source != previous else '', t.target, t.guard.text))
        previous = t.source
    return lines


def _named(guards):
    named = definitions(guards)
    if not named:
        return []
    return ['', 'Where:', ''] + ['- **%s** = %s%s' % (name, expr.body.text, _means(expr))
                                 for name, expr in named.items()]


def _facts(guards, facts_class):
    """The facts the guards read, in the order of the facts' fields."""
    facts = list(facts_read(guards).values())
    if not facts:
        return []
    facts.sort(key=lambda fact: facts_class._fields.index(fact.field))
    return ['', 'Facts, read after every action:', ''] + ['- **%s**%s%s' % (fact.text, _field(fact), _means(fact))
                                                          for fact in facts]


def _field(fact):
    """How the fact reads its field, unless its text says it already."""
    if isinstance(fact, Equals):
        return ' (`%s == %r`)' % (fact.field, fact.value)
    return '' if fact.text == fact.field else ' (`%s`)' % fact.field


def _means(expr):
    return ': %s' % expr.means if expr.means else ''
