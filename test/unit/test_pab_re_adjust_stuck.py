"""A re-adjust that repeats itself ends with the reason, not at the state cap.

The twin, started twisted by 0.55 rad (the rotation encoder zeroed on the
twist, `bench/pab_clamp_sweep --random-joints 8 --seed 2929`), ran Clamp
Sideways RIGHT round the same pass until the 60-state cap: each full front
clamp, the front lying where the encoder does not say, pulled the rear to
0.113-0.116 rad, off the straight band; the rear turned back, the front
aligned, and the front clamp pulled it off again. Here a kinematic robot
(test/unit/kinematic_robot.py) whose full front clamp does the same.
"""
import collections
import math

import pytest

from pirate.sequencer.pabs.base import PabFailed
from pirate.sequencer.pabs.clamp import Clamp

from kinematic_robot import BOOK, KinematicRobot, run

GUARDS = BOOK.for_diameter(90)


class PulledByTheFront(KinematicRobot):
    """A full front clamp leaves the rear at ``pulled_to`` rad (None: where it is)."""

    def __init__(self, rear_roll, pulled_to):
        KinematicRobot.__init__(self, rear_roll, 0.0, front_tilt=0.0)
        self.pulled_to = list(pulled_to)

    def clamp(self, part, kind='clamp'):
        KinematicRobot.clamp(self, part, kind)
        if part == 'front' and kind == 'clamp' and self.pulled_to:
            roll = self.pulled_to.pop(0)
            if roll is not None:
                self.rear = roll
                self.front = roll - self.rotation


def full_front_clamps(robot):
    return robot.executed.count('clamp front')


def test_the_same_roll_after_every_front_clamp_aborts_with_the_reason():
    robot = PulledByTheFront(1.45, [1.686, 1.687, 1.685] * 10)
    with pytest.raises(PabFailed) as failed:
        run(Clamp(), robot)
    passes = int(GUARDS.re_adjust['same_roll_passes'])
    assert full_front_clamps(robot) == passes
    assert len(robot.executed) < GUARDS.max_primitives
    assert 'does not converge' in str(failed.value)
    assert '1.685 to 1.687 rad' in str(failed.value) and 'rotation encoder' in str(failed.value)


def test_a_re_adjust_that_moves_is_not_called_stuck():
    """Rolls that differ by more than same_roll_rad, then straight: it ends clamped."""
    step = float(GUARDS.re_adjust['same_roll_rad']) * 2
    robot = PulledByTheFront(1.45, [1.72, 1.72 - step, 1.72 - 2 * step, None])
    run(Clamp(), robot)
    low, high = GUARDS.region('straight')
    assert low <= robot.rear <= high
    assert full_front_clamps(robot) == 4


View = collections.namedtuple('View', 'orientation')
Ctx = collections.namedtuple('Ctx', 'feed guards')


class Rolls(object):
    """A feed whose robot lies at the next of ``rolls`` each time it is read."""

    def __init__(self, rolls):
        self.rolls = list(rolls)

    def latest(self):
        return View(self.rolls.pop(0))


def watch(rolls):
    """Clamp Straight's watch after each of ``rolls`` (rad); the reason it raised, or None."""
    clamp, ctx = Clamp(), Ctx(Rolls(rolls), GUARDS)
    try:
        for _ in rolls:
            clamp._watch_re_adjust(ctx)
    except PabFailed as failed:
        return str(failed)
    return None


def test_only_passes_in_a_row_count():
    """A front clamp that ends straight (and a pass re-adjusted only to
    align) starts the count again; so does one off by more than same_roll_rad."""
    off, straight = 1.686, math.pi / 2
    far = off + 2 * float(GUARDS.re_adjust['same_roll_rad'])
    assert watch([off, off, straight, off, off]) is None
    assert watch([off, far, off, far]) is None
    assert 'does not converge' in watch([off, far, off, off, off])
