"""The simulator's lockstep with the stack (pirate.sim.lockstep, doc/clock.md).

The simulator steps on only once the stack took in the cycle it published,
a consumer that drops out stops holding it, and a frozen stack holds it only
for the wall bound. The clock the bound is judged on is a fake here: no
test depends on how fast this machine runs.
"""
import threading

import pytest

from pirate.sim.lockstep import Lockstep


class FakeWall(object):
    """A wall clock that moves ``step_s`` each time it is read."""

    def __init__(self, step_s):
        self.step_s = step_s
        self.now = 0.0

    def __call__(self):
        self.now += self.step_s
        return self.now


CYCLE_S = 0.1   # a Mega cycle of simulated time


def test_an_acknowledged_cycle_lets_the_simulator_step_on():
    step = Lockstep(bound_s=1.0, wall=FakeWall(0.0))
    step.published(1.0)
    step.acknowledged(1.0)
    assert step.wait(lambda: True) and step.overruns == 0


def _running(wall):
    """A lockstep whose consumer has acknowledged a first cycle."""
    step = Lockstep(bound_s=1.0, wall=wall)
    step.published(1.0)
    step.acknowledged(1.0)
    return step


def test_a_held_consumer_holds_the_simulator_until_the_bound():
    """Nothing acknowledges: the simulator steps on at the bound (the wall
    clock moves 0.25 s at each look)."""
    wall = FakeWall(0.25)
    step = _running(wall)
    step.published(1.0 + CYCLE_S)
    assert not step.wait(lambda: True)
    assert step.overruns == 1 and wall.now >= 1.0


def test_an_acknowledgement_of_an_earlier_cycle_does_not_count():
    step = _running(FakeWall(0.25))
    step.acknowledged(1.0)         # late: the cycle before
    step.published(1.0 + CYCLE_S)
    assert not step.wait(lambda: True)


def test_a_late_acknowledgement_stamped_with_the_cycle_before_does_not_count():
    """The consumer's acknowledgement of the cycle before arrives after the
    new cycle was published: counting it let the simulator run cycles ahead
    of the manager, whose feedback watchdog then saw 0.38 s of silence."""
    step = _running(FakeWall(0.25))
    step.published(1.0 + CYCLE_S)
    step.acknowledged(1.0)
    assert not step.wait(lambda: True)
    step.published(1.0 + 2 * CYCLE_S)
    step.acknowledged(1.0 + 2 * CYCLE_S - 0.02)    # its clock one PICO step behind the cycle's
    assert step.wait(lambda: True)


def test_nobody_consuming_holds_nothing():
    step = Lockstep(bound_s=1.0, wall=FakeWall(0.0))
    step.published(1.0 + CYCLE_S)
    assert step.wait(lambda: False) and step.overruns == 0


def test_a_consumer_that_drops_out_releases_the_wait():
    alive = [True, True, False]     # its connection closes while the simulator waits
    step = _running(FakeWall(0.0))
    step.published(1.0 + CYCLE_S)
    assert step.wait(lambda: alive.pop(0)) and step.overruns == 0


def test_the_acknowledgement_wakes_a_waiting_simulator():
    """The wall clock stands still: only the consumer's acknowledgement can end the wait."""
    step = _running(FakeWall(0.0))
    step.published(1.0 + CYCLE_S)
    consumer = threading.Thread(target=step.acknowledged, args=(1.0 + CYCLE_S,))
    consumer.start()
    assert step.wait(lambda: True)
    consumer.join()


def test_before_the_first_acknowledgement_nobody_waits():
    """A stack starting up: the manager's acknowledgement publisher is
    connected before its state subscription is."""
    step = Lockstep(bound_s=1.0, wall=FakeWall(0.25))
    step.published(1.0 + CYCLE_S)
    assert step.wait(lambda: True) and step.overruns == 0


def test_the_bound_must_be_positive():
    with pytest.raises(ValueError, match='above 0'):
        Lockstep(bound_s=0.0)
