"""SimpleGoalClient (pirate.supervisory.goal_client): actionlib's simple
client interface without its race. A server that ends the goal before
``send_goal`` has returned (the worst case: the transition delivered inside
the call) must still be seen ended, with each callback called once. A
scripted ActionClient, no master."""
import actionlib
import pytest
import rospy
from actionlib_msgs.msg import GoalStatus

from pirate.msg import PirateResult
from pirate.supervisory.goal_client_ros import SimpleGoalClient

CommState = actionlib.CommState


class Goal(object):
    """One goal's client state, shared by every handle wrapping it (as actionlib's CommStateMachine)."""

    def __init__(self):
        self.comm, self.status, self.result, self.cancelled = CommState.WAITING_FOR_GOAL_ACK, GoalStatus.PENDING, None, 0


class Handle(object):
    """A fresh wrapper per call, equal when it wraps the same goal (as ClientGoalHandle)."""

    def __init__(self, goal):
        self.goal = goal

    def __eq__(self, other):
        return isinstance(other, Handle) and other.goal is self.goal

    def get_comm_state(self):
        return self.goal.comm

    def get_goal_status(self):
        return self.goal.status

    def get_result(self):
        return self.goal.result

    def get_goal_status_text(self):
        return 'text'

    def cancel(self):
        """As actionlib's: counts the cancel and waits for its ack, even for an ended goal."""
        self.goal.cancelled += 1
        self.goal.comm = CommState.WAITING_FOR_CANCEL_ACK


class FastServerClient(object):
    """An ActionClient whose server answers each goal (``ending``) before send_goal returns."""

    def __init__(self, ending):
        self.ending, self.goals = ending, []

    def send_goal(self, goal, transition_cb=None, feedback_cb=None):
        state = Goal()
        self.goals.append(state)
        for comm, status in self.ending:
            state.comm, state.status = comm, status
            if status in (GoalStatus.SUCCEEDED, GoalStatus.REJECTED):
                state.result = PirateResult(message='ended at once')
            transition_cb(Handle(state))
        return Handle(state)


@pytest.fixture(autouse=True)
def wall_rostime():
    rospy.rostime.set_rostime_initialized(True)     # no master: ROS time is the wall clock


SUCCEEDED_AT_ONCE = [(CommState.ACTIVE, GoalStatus.ACTIVE), (CommState.DONE, GoalStatus.SUCCEEDED)]
REJECTED_AT_ONCE = [(CommState.DONE, GoalStatus.REJECTED)]


def test_a_goal_ended_before_send_goal_returned_is_seen_ended():
    calls = []
    client = SimpleGoalClient(client=FastServerClient(SUCCEEDED_AT_ONCE))
    client.send_goal('clamp', done_cb=lambda state, result: calls.append(('done', state, result.message)),
                     active_cb=lambda: calls.append(('active',)))
    assert client.wait_for_result(rospy.Duration(1.0))
    assert client.get_state() == GoalStatus.SUCCEEDED and client.get_result().message == 'ended at once'
    assert calls == [('active',), ('done', GoalStatus.SUCCEEDED, 'ended at once')]


def test_a_goal_rejected_at_once_is_done_without_being_active():
    calls = []
    client = SimpleGoalClient(client=FastServerClient(REJECTED_AT_ONCE))
    client.send_goal('clamp', done_cb=lambda state, result: calls.append(('done', state)),
                     active_cb=lambda: calls.append(('active',)))
    assert client.wait_for_result(rospy.Duration(1.0))
    assert calls == [('done', GoalStatus.REJECTED)]


def test_a_goal_still_running_times_out_and_cancel_reaches_its_handle():
    server = FastServerClient([(CommState.ACTIVE, GoalStatus.ACTIVE)])
    client = SimpleGoalClient(client=server)
    assert client.get_state() == GoalStatus.LOST and client.get_result() is None
    client.send_goal('drive')
    assert not client.wait_for_result(rospy.Duration(0.2))
    assert client.get_state() == GoalStatus.ACTIVE
    client.cancel_goal()
    assert server.goals[0].cancelled == 1


def test_transitions_of_an_earlier_goal_are_ignored():
    calls = []
    server = FastServerClient(SUCCEEDED_AT_ONCE)
    client = SimpleGoalClient(client=server)
    client.send_goal('first')
    first = server.goals[0]
    server.ending = [(CommState.ACTIVE, GoalStatus.ACTIVE)]
    client.send_goal('second', done_cb=lambda *args: calls.append(args))
    client._on_transition(Handle(first))                 # a late status of the first goal
    assert calls == [] and client.get_state() == GoalStatus.ACTIVE


def test_a_cancel_after_the_goal_ended_leaves_it_ended():
    """actionlib's handle.cancel() on an ended goal would set it waiting for
    a cancel ack forever (a Home cancelled at random just after it succeeded)."""
    server = FastServerClient(SUCCEEDED_AT_ONCE)
    client = SimpleGoalClient(client=server)
    client.send_goal('home')
    client.cancel_goal()
    assert server.goals[0].cancelled == 0
    assert client.wait_for_result(rospy.Duration(0.2)) and client.get_state() == GoalStatus.SUCCEEDED
