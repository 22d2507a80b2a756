"""RobotFeed: event-driven guard waiting, cancel, robot-time timeout, watchdog.

The watchdog's wall clock is injected (a fake clock), so no test depends
on how fast the machine is; threads signal with events, never with sleeps.
"""
import math
import threading
import time

import pytest

from pirate.state.feed import Cancelled, FeedbackLost, RobotFeed, RobotView, TimedOut

BOUND_S = 5.0     # a wait that should end promptly must end within this


class FakeClock(object):
    """A monotonic clock the test moves by hand."""

    def __init__(self, now=100.0):
        self.now = now

    def __call__(self):
        return self.now


def view(stamp, **angles):
    base = {'bend_i': 0.0, 'rotation': 0.0}
    base.update(angles)
    return RobotView(base, math.pi / 2, 0.0, 0.0, stamp)


@pytest.fixture
def clock():
    return FakeClock()


@pytest.fixture
def feed(clock):
    return RobotFeed(feedback_timeout=0.3, clock=clock)


def run_wait(feed, guard, timeout=15.0):
    """Start wait_until in a thread; return once it has looked at a state.

    The first guard evaluation happens under the feed's lock, after which
    the wait holds its start stamp: states pushed later are seen by it.
    """
    result = {}
    started = threading.Event()

    def watched(v):
        started.set()
        return guard(v)

    def body():
        try:
            result['view'] = feed.wait_until(watched, timeout, 'test guard')
        except Exception as error:  # pylint: disable=broad-except
            result['error'] = error
    thread = threading.Thread(target=body, daemon=True)
    thread.start()
    assert started.wait(BOUND_S) or 'error' in result
    return thread, result


def test_returns_at_once_when_guard_already_holds(feed):
    feed.push(view(1.0, bend_i=-0.8))
    got = feed.wait_until(lambda v: v.angles['bend_i'] <= -0.77, 15.0)
    assert got.angles['bend_i'] == -0.8


def test_returns_on_the_state_that_satisfies_the_guard(feed):
    feed.push(view(1.0, bend_i=0.0))
    thread, result = run_wait(feed, lambda v: v.angles['bend_i'] <= -0.77)
    for i, angle in enumerate((-0.3, -0.6, -0.78)):
        assert 'view' not in result
        feed.push(view(1.1 + 0.1 * i, bend_i=angle))
    thread.join(BOUND_S)
    assert not thread.is_alive()
    assert result['view'].angles['bend_i'] == -0.78


def test_cancel_from_another_thread_ends_the_wait(feed):
    feed.push(view(1.0))
    thread, result = run_wait(feed, lambda v: False)
    start = time.monotonic()
    feed.cancel()
    thread.join(BOUND_S)
    assert not thread.is_alive()
    assert isinstance(result['error'], Cancelled)
    # ends on the notify, well inside one second even on a loaded machine
    assert time.monotonic() - start < 1.0


def test_cancel_sticks_until_cleared(feed):
    feed.push(view(1.0))
    feed.cancel()
    assert feed.cancelled
    with pytest.raises(Cancelled):
        feed.wait_until(lambda v: True, 15.0)
    with pytest.raises(Cancelled):
        feed.check()
    feed.clear_cancel()
    assert not feed.cancelled
    assert feed.wait_until(lambda v: True, 15.0).stamp == 1.0


def test_timeout_runs_on_robot_time(feed, clock):
    feed.push(view(10.0))
    thread, result = run_wait(feed, lambda v: False, timeout=15.0)
    # 14.9 s of robot time: still waiting
    for stamp in (12.0, 20.0, 24.9):
        clock.now += 0.1
        feed.push(view(stamp))
    assert 'error' not in result
    clock.now += 0.1
    feed.push(view(25.2))
    thread.join(BOUND_S)
    assert isinstance(result['error'], TimedOut)
    assert 'test guard' in str(result['error']) and '15.0' in str(result['error'])


def test_no_timeout_however_long_the_wall_clock_if_robot_time_stands(feed, clock):
    """Robot stamps decide the timeout; fresh states keep the watchdog quiet."""
    feed.push(view(5.0))
    thread, result = run_wait(feed, lambda v: v.angles['bend_i'] < -1, timeout=1.0)
    for _ in range(20):
        clock.now += 0.2
        feed.push(view(5.5))
    assert 'error' not in result and thread.is_alive()
    feed.push(view(5.6, bend_i=-2.0))
    thread.join(BOUND_S)
    assert result['view'].angles['bend_i'] == -2.0


def test_feedback_lost_on_wall_clock(feed, clock):
    feed.push(view(1.0))
    thread, result = run_wait(feed, lambda v: False)
    assert feed.fresh()
    clock.now += 0.31          # no state for longer than the feedback timeout
    thread.join(BOUND_S)       # the wait polls the clock: ends within one poll
    assert not thread.is_alive()
    assert isinstance(result['error'], FeedbackLost)
    assert 'no robot state' in str(result['error'])
    assert not feed.fresh()
    assert feed.since_last_state() == pytest.approx(0.31)


def test_feedback_lost_before_the_first_state(feed):
    assert feed.latest() is None and not feed.fresh()
    assert feed.since_last_state() == math.inf
    with pytest.raises(FeedbackLost):
        feed.wait_until(lambda v: True, 15.0)


def test_cancel_wins_over_feedback_loss(feed, clock):
    feed.push(view(1.0))
    clock.now += 10.0
    feed.cancel()
    with pytest.raises(Cancelled):
        feed.check()


def test_a_state_sent_ahead_of_the_subscribers_clock_counts_from_when_it_was_sent(feed, clock):
    """Simulated time: the manager's /clock lagged 0.2 s when the state came;
    once its clock catches up the state is 0.25 s old, not 0.45 s."""
    feed.push(view(1.0), sent_s=clock.now + 0.2)
    clock.now += 0.45
    assert feed.since_last_state() == pytest.approx(0.25) and feed.fresh()


def test_a_state_sent_behind_the_subscribers_clock_counts_from_its_arrival(feed, clock):
    feed.push(view(1.0), sent_s=clock.now - 0.2)
    clock.now += 0.25
    assert feed.since_last_state() == pytest.approx(0.25)
