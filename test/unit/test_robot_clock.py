"""RobotClock: a simulated robot that runs late is late, not silent.

Fake wall and sim clocks; every figure is checked against the definition:
the wall clock, held at ``slack_s`` past the last advance of simulated time,
going on from where it stood when simulated time moves again.
"""
import time

import pytest

from pirate.state.robot_clock import RobotClock, silence_clock


class Clocks(object):
    def __init__(self):
        self.wall, self.sim = 100.0, 1.0

    def clock(self, slack_s=0.15):
        return RobotClock(lambda: self.sim, wall=lambda: self.wall, slack_s=slack_s)


def test_on_time_the_robot_clock_is_the_wall_clock():
    c = Clocks()
    clock = c.clock()
    for _ in range(50):
        c.wall += 0.02
        c.sim += 0.08          # x4: /clock ticks every 20 ms wall
        assert clock() == pytest.approx(c.wall)


def test_a_stalled_simulation_holds_the_clock_and_the_stall_is_not_counted_after():
    c = Clocks()
    clock = c.clock()
    c.wall += 0.02
    c.sim += 0.02
    before = clock()
    c.wall += 0.8                       # the simulator descheduled 0.8 s: sim time stands
    assert clock() == pytest.approx(before + 0.15)
    c.sim += 0.02                       # it runs again: its 0.02 s count, the stall not
    assert clock() == pytest.approx(before + 0.17)
    c.wall += 0.1
    c.sim += 0.1
    assert clock() == pytest.approx(before + 0.27)


def test_a_robot_that_keeps_time_but_stops_reporting_is_timed_in_wall_seconds():
    """The watchdogs' case: time runs, states do not; the clock is the wall,
    however rarely it is read."""
    c = Clocks()
    clock = c.clock()
    start = clock()
    for _ in range(20):
        c.wall += 0.02
        c.sim += 0.02
    assert clock() - start == pytest.approx(0.4)


def test_the_clock_never_runs_backwards():
    c = Clocks()
    clock = c.clock()
    seen = [clock()]
    for step, (dw, ds) in enumerate([(0.3, 0.0), (0.01, 0.0), (0.0, 0.1), (0.5, 0.0), (0.2, 0.3)] * 4):
        c.wall += dw
        c.sim += ds
        seen.append(clock())
    assert seen == sorted(seen)


def test_a_real_robot_is_timed_on_the_wall_clock():
    assert silence_clock(False, lambda: 0.0) is time.monotonic
    assert isinstance(silence_clock(True, lambda: 0.0), RobotClock)
