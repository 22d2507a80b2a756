"""The one goal-waiting helper (pirate.supervisory.goal_client) of the
mission runner and the mission executive: its end states, its time limit
in robot time with the goal cancelled, a shutdown, a cancel from another
thread; and how the executive reads each end. A scripted ActionClient and
clock, no master; threads meet on events."""
import threading

import actionlib
import pytest
from actionlib_msgs.msg import GoalStatus

from pirate.msg import PirateResult
from pirate.supervisory import executive_node
from pirate.supervisory.goal_client_ros import GoalClient

WAIT_S = 10.0


class Handle(object):
    def __init__(self):
        self.state, self.status, self.result = actionlib.CommState.ACTIVE, GoalStatus.ACTIVE, None
        self.cancelled = threading.Event()

    def get_comm_state(self):
        return self.state

    def get_goal_status(self):
        return self.status

    def get_result(self):
        return self.result

    def cancel(self):
        """As actionlib's: sent whatever the state, and the handle then waits for a
        cancel ack (on a goal that has ended, one that never comes)."""
        self.cancelled.set()
        self.state = actionlib.CommState.WAITING_FOR_CANCEL_ACK


class Client(object):
    """An ActionClient whose goal ends when the test says (``finish``)."""

    def __init__(self):
        self.handle, self.sent, self._cb = Handle(), threading.Event(), None

    def send_goal(self, goal, transition_cb, feedback_cb=None):
        self._cb = transition_cb
        self.sent.set()
        return self.handle

    def finish(self, status, message='done', notify=True):
        """The goal ends; ``notify`` False: its transition callback has not run yet."""
        self.handle.result = PirateResult(message=message)
        self.handle.state, self.handle.status = actionlib.CommState.DONE, status
        if notify:
            self._cb(self.handle)


class RobotClock(object):
    """Robot time that moves only when the waiter looks at it (1 s a look)."""

    def __init__(self, step_s=1.0):
        self.t, self.step = 100.0, step_s

    def __call__(self):
        self.t += self.step
        return self.t


def _in_thread(goals):
    out = {}
    thread = threading.Thread(target=lambda: out.update(ending=goals.run(object())), daemon=True)
    thread.start()
    return thread, out


@pytest.mark.parametrize('status, word', [(GoalStatus.SUCCEEDED, 'succeeded'), (GoalStatus.ABORTED, 'aborted'),
                                          (GoalStatus.PREEMPTED, 'preempted'), (GoalStatus.REJECTED, 'rejected'),
                                          (GoalStatus.RECALLED, 'recalled')])
def test_a_goal_that_ends_is_reported_in_words_with_its_result(status, word):
    client = Client()
    goals = GoalClient(client, 600.0, RobotClock(0.0), lambda: False)
    thread, out = _in_thread(goals)
    assert client.sent.wait(WAIT_S)
    client.finish(status, 'the message')
    thread.join(WAIT_S)
    assert out['ending'].status == word and out['ending'].message == 'the message'
    assert not client.handle.cancelled.is_set()


def test_no_result_within_the_robot_time_limit_cancels_the_goal():
    client, clock = Client(), RobotClock(1.0)
    goals = GoalClient(client, 5.0, clock, lambda: False)
    ending = goals.run(object())             # nothing ever ends it; robot time runs out
    assert ending.status == 'timeout' and 'no result within 5 s' in ending.message
    assert client.handle.cancelled.is_set() and ending.result is None
    assert 105.0 <= clock.t <= 108.0         # gave up at the limit, not before, not long after


def test_a_shutdown_cancels_the_goal_and_says_so():
    client, stopping = Client(), threading.Event()
    goals = GoalClient(client, 600.0, RobotClock(0.0), stopping.is_set)
    thread, out = _in_thread(goals)
    assert client.sent.wait(WAIT_S)
    stopping.set()
    thread.join(WAIT_S)
    assert out['ending'].status == 'interrupted' and client.handle.cancelled.is_set()


def test_cancel_from_another_thread_reaches_the_running_goal():
    client = Client()
    goals = GoalClient(client, 600.0, RobotClock(0.0), lambda: False)
    thread, out = _in_thread(goals)
    assert client.sent.wait(WAIT_S)
    goals.cancel()
    assert client.handle.cancelled.wait(WAIT_S)
    client.finish(GoalStatus.PREEMPTED, 'cancelled')
    thread.join(WAIT_S)
    assert out['ending'].status == 'preempted'
    goals.cancel()                            # nothing runs: nothing to cancel, no error


def test_a_cancel_that_meets_the_goal_ending_is_not_sent():
    """The executive cancels just as the goal ends, before the waiter has seen
    it: a cancel sent then leaves actionlib waiting for an ack that never comes,
    and the waiter (robot time standing still here) would never return."""
    client = Client()
    goals = GoalClient(client, 600.0, RobotClock(0.0), lambda: False)
    thread, out = _in_thread(goals)
    assert client.sent.wait(WAIT_S)
    client.finish(GoalStatus.SUCCEEDED, 'clamped', notify=False)
    goals.cancel()
    thread.join(WAIT_S)
    assert not client.handle.cancelled.is_set()
    assert out['ending'].status == 'succeeded' and out['ending'].message == 'clamped'


@pytest.mark.parametrize('status, seen', [('timeout', 'aborted'), ('interrupted', 'aborted'),
                                          ('recalled', 'rejected'), ('succeeded', 'succeeded')])
def test_the_executive_retries_a_timeout_and_never_a_recall(status, seen):
    from pirate.supervisory.goal_client_ros import Ending
    result = PirateResult(message='m') if status == 'succeeded' else None
    report = executive_node.report(Ending(status, 'm', result), 12.5, 2.5)
    assert report.status == seen and report.odometry_mm == 12.5 and report.message == 'm'
    assert report.junction_missing is False


@pytest.mark.parametrize('found, at', [(416.0, 1416.0), (float('nan'), None)])
def test_the_junction_is_placed_in_the_robots_odometry_not_the_goals(found, at):
    """The result's junction_odometry counts from the goal's start; the
    localiser works in the robot's odometry (the goal started at 1000 mm)."""
    from pirate.supervisory.goal_client_ros import Ending
    result = PirateResult(message='m', junction_odometry=found)
    report = executive_node.report(Ending('succeeded', 'm', result), 1900.0, 1000.0)
    assert report.junction_odometry_mm == at


class Server(object):
    """An ActionClient's wait_for_server that answers after ``answers_after`` asks."""

    def __init__(self, answers_after):
        self.asks, self.answers_after = 0, answers_after

    def wait_for_server(self, timeout):
        self.asks += 1
        return self.answers_after is not None and self.asks >= self.answers_after


def test_waiting_for_the_server_polls_in_wall_time_until_it_answers_or_the_time_is_up():
    from pirate.supervisory.goal_client_ros import wait_for_server
    server = Server(3)
    assert wait_for_server(server, 30.0) and server.asks == 3
    absent = Server(None)
    assert not wait_for_server(absent, 0.3) and absent.asks >= 2
