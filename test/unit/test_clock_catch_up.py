"""A node's simulated clock catching up with a cycle the simulator already
sent (pirate.state.clock_ros.catch_up): /clock and the Small States come on
separate threads, so a cycle can be handled before the node's clock moved."""
import threading

import pytest
import rospy

from pirate.state.clock_ros import catch_up


@pytest.fixture
def sim_clock():
    """Simulated time at 10.0 s, set as the /clock thread sets it; wall time after."""
    rospy.rostime.set_rostime_initialized(True)
    rospy.rostime._set_rostime(rospy.Time.from_sec(10.0))
    yield lambda t_s: rospy.rostime._set_rostime(rospy.Time.from_sec(t_s))
    rospy.rostime.switch_to_wallclock()


class Waited(threading.Condition):
    """rospy's clock condition, saying when someone waits on it."""

    def __init__(self):
        super(Waited, self).__init__()
        self.waiting = threading.Event()

    def wait(self, timeout=None):
        self.waiting.set()
        return super(Waited, self).wait(timeout)


def test_a_cycle_handled_before_its_clock_waits_for_it(sim_clock, monkeypatch):
    """The /clock thread sets the cycle's five steps once the Small State waits."""
    cond = Waited()
    monkeypatch.setattr(rospy.rostime, '_rostime_cond', cond)

    def clock_thread():
        if cond.waiting.wait(30.0):
            for step in range(1, 6):
                sim_clock(10.0 + 0.02 * step)

    steps = threading.Thread(target=clock_thread)
    steps.start()
    assert catch_up(10.099, bound_s=30.0) >= 10.099
    steps.join()


def test_a_clock_that_never_comes_is_waited_for_at_most_the_bound(sim_clock):
    assert catch_up(10.099, bound_s=0.01) == 10.0


def test_a_clock_already_there_does_not_wait(sim_clock):
    sim_clock(10.1)
    assert catch_up(10.099, bound_s=0.0) == pytest.approx(10.1)
