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


def test_after_an_overrun_a_late_acknowledgement_of_the_cycle_before_does_not_count():
    """The simulator stepped on unacknowledged; the consumer's acknowledgement
    of that cycle arrives after the new cycle was published: counting it
    would let the simulator run a cycle ahead of the manager for good."""
    step = _running(FakeWall(0.25))
    step.published(1.0 + CYCLE_S)
    assert not step.wait(lambda: True)             # overrun
    step.published(1.0 + 2 * CYCLE_S)
    step.acknowledged(1.0 + CYCLE_S - 0.02)        # late: of the cycle stepped over
    assert not step.wait(lambda: True)
    step.published(1.0 + 3 * CYCLE_S)
    step.acknowledged(1.0 + 3 * CYCLE_S - 4 * 0.02)    # of this cycle, its clock four steps behind
    assert step.wait(lambda: True)


def test_in_step_the_next_acknowledgement_is_of_the_next_cycle_whatever_its_stamp():
    """Its clock thread had taken none of the cycle's five /clock steps when
    the state came (beside 8 busy processes on 2 cores): the state, made
    from this cycle's Small States, is stamped with the cycle before's time."""
    step = _running(FakeWall(0.25))
    step.published(1.0 + CYCLE_S)
    step.acknowledged(1.0)
    assert step.wait(lambda: True) and step.overruns == 0
    assert step.worst_lag_s == pytest.approx(CYCLE_S)
    step.published(1.0 + 2 * CYCLE_S)
    step.acknowledged(1.0 + CYCLE_S)
    assert step.wait(lambda: True)
    step.published(1.0 + 3 * CYCLE_S)
    assert not step.wait(lambda: True)              # one acknowledgement, one cycle


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
