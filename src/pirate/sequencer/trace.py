"""The trace of one goal: every motion primitive with robot times and outcome.

Feedback is a lossy stream (a client that connects late or a busy machine
drops messages), so what ran is also recorded here and returned in the
goal's result: the demo and the tests read the trace, not the feedback.
Times are robot time (s, the stamp of the robot state: simulated time under
``/clock``). Pure Python.
"""
import collections
import re

REACHED = 'reached'

#: One executed primitive; ``end`` is None while it runs.
Step = collections.namedtuple('Step', 'name guard start end outcome')

#: A guard's numbers: joints, their current values (rad) and thresholds (rad).
GuardNumbers = collections.namedtuple('GuardNumbers', 'joints values thresholds')

# The guard texts the primitives write (pirate.sequencer.primitives,
# guards.PairGuard.describe): "bend_i <= -0.77 and bend_ii >= 0.35",
# "front_tilt >= 0.400", "|rotation - 0.100| <= 0.0425".
_BOUND = re.compile(r'(?<!\|)\b([a-z_]+) (?:<=|>=) (-?\d+(?:\.\d+)?)')
_AROUND = re.compile(r'\|([a-z_]+) - (-?\d+(?:\.\d+)?)\| <= (\d+(?:\.\d+)?)')


class Trace(object):
    """Primitives of one goal, in order, each started and ended once."""

    def __init__(self):
        self.steps = []

    @property
    def running(self):
        """The step that has started and not ended, or None."""
        if self.steps and self.steps[-1].end is None:
            return self.steps[-1]
        return None

    def start(self, name, guard, now):
        """Primitive ``name`` starts at robot time ``now`` waiting for ``guard``."""
        self.end(now, REACHED)
        self.steps.append(Step(name, guard, now, None, ''))

    def end(self, now, outcome):
        """End the running primitive (if any) with ``outcome``."""
        step = self.running
        if step is not None:
            self.steps[-1] = step._replace(end=now, outcome=outcome)


def guard_numbers(text, angles):
    """:data:`GuardNumbers` of a guard text against joint ``angles`` (rad).

    A bound "joint <= x" gives the joint's angle against x; "|joint - t| <=
    tol" gives |angle - t| against tol. Joints not in ``angles`` are left out.
    """
    joints, values, thresholds = [], [], []
    for joint, target, tolerance in _AROUND.findall(text):
        if joint in angles:
            joints.append(joint)
            values.append(abs(angles[joint] - float(target)))
            thresholds.append(float(tolerance))
    for joint, bound in _BOUND.findall(text):
        if joint in angles:
            joints.append(joint)
            values.append(angles[joint])
            thresholds.append(float(bound))
    return GuardNumbers(joints, values, thresholds)
