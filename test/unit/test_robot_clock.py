"""RobotClock: a simulated robot that runs late is late, not silent.

Fake wall clock; every figure is checked against the definition: the wall
clock, held at ``slack_s`` past the last tick of simulated time, going on
from where it stood at the next tick.
"""
import pytest

from pirate.state.robot_clock import RobotClock


class Wall(object):
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


def run(wall, clock, wall_s, tick_every_s=0.02):
    """Let ``wall_s`` pass with simulated time ticking every ``tick_every_s``."""
    for _ in range(int(round(wall_s / tick_every_s))):
        wall.now += tick_every_s
        clock.tick()


def test_on_time_the_robot_clock_is_the_wall_clock():
    wall = Wall()
    clock = RobotClock(wall)
    start = clock()
    run(wall, clock, 1.0)
    assert clock() - start == pytest.approx(1.0)


def test_a_stalled_simulation_holds_the_clock_and_the_stall_is_not_counted_after():
    wall = Wall()
    clock = RobotClock(wall)
    run(wall, clock, 0.1)
    before = clock()
    wall.now += 0.8                     # the simulator descheduled 0.8 s: no tick
    assert clock() == pytest.approx(before + 0.15)
    clock.tick()                        # it runs again: no jump
    assert clock() == pytest.approx(before + 0.15)
    run(wall, clock, 0.1)
    assert clock() == pytest.approx(before + 0.25)


def test_a_robot_that_keeps_time_but_stops_reporting_is_timed_in_wall_seconds():
    """The watchdogs' case: time runs, states do not; read rarely, the clock
    is still the wall."""
    wall = Wall()
    clock = RobotClock(wall)
    start = clock()
    run(wall, clock, 0.4)
    assert clock() - start == pytest.approx(0.4)


def test_before_simulated_time_starts_the_clock_stands_and_goes_on_without_a_jump():
    wall = Wall()
    clock = RobotClock(wall)
    wall.now += 0.5                     # the node is up, the simulator not yet
    heard = clock()
    clock.tick()
    run(wall, clock, 0.1)
    assert clock() - heard == pytest.approx(0.1)


def test_the_clock_never_runs_backwards():
    wall = Wall()
    clock = RobotClock(wall)
    seen = [clock()]
    for dw, tick in [(0.3, False), (0.01, True), (0.0, True), (0.5, False), (0.2, True)] * 4:
        wall.now += dw
        if tick:
            clock.tick()
        seen.append(clock())
    assert all(later >= earlier - 1e-9 for earlier, later in zip(seen, seen[1:])), seen
