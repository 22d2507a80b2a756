"""SimpleGoalClient (pirate.supervisory.goal_client): actionlib's simple
client interface without its race. A server that ends the goal before
``send_goal`` has returned (the worst case: the transition delivered inside
the call) must still be seen ended, with each callback called once. A
scripted ActionClient, no master."""
import actionlib
import actionlib.action_client
import pytest
import rospy
from actionlib_msgs.msg import GoalID, GoalStatus, GoalStatusArray
from actionlib_msgs.msg import GoalStatus as GoalStatusMsg

from pirate.msg import PirateAction, PirateActionResult, PirateGoal, PirateResult
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


# --- actionlib's own client state machine, driven message by message ----------------------

class Wire(object):
    """actionlib's GoalManager with the topics replaced: what the client sent,
    and the server's messages delivered when the test says."""

    def __init__(self):
        self.manager = actionlib.action_client.GoalManager(PirateAction)
        self.sent = []                   # ('goal', id) / ('cancel', id), in order
        self.manager.register_send_goal_fn(lambda goal: self.sent.append(('goal', goal.goal_id.id)))
        self.manager.register_cancel_fn(lambda goal_id: self.sent.append(('cancel', goal_id.id)))

    def send_goal(self, goal, transition_cb=None, feedback_cb=None):
        return self.manager.init_goal(goal, transition_cb, feedback_cb)

    def status(self, *statuses):
        """A status array from the server: (goal id, GoalStatus) pairs."""
        self.manager.update_statuses(GoalStatusArray(status_list=[
            GoalStatusMsg(goal_id=GoalID(id=goal_id), status=status) for goal_id, status in statuses]))

    def result(self, goal_id, status, message):
        self.manager.update_results(PirateActionResult(
            status=GoalStatusMsg(goal_id=GoalID(id=goal_id), status=status), result=PirateResult(message=message)))


def test_a_goal_cancelled_before_the_server_acknowledged_it_keeps_its_result():
    """A goal/cancel storm: 9 goals ended LOST at the client although the server
    published their results. Cancelled at once, actionlib's client waited for
    the cancel's ack and took the next status array not listing the goal yet
    (sent for another goal) for a goal the server had lost."""
    wire = Wire()
    client = SimpleGoalClient(client=wire)
    client.send_goal(PirateGoal(name=1))
    goal_id = wire.sent[0][1]
    client.cancel_goal()                                        # before any status lists the goal
    wire.status(('another-goal', GoalStatus.SUCCEEDED))         # the server has not seen it yet
    assert not client.wait_ended(0.0)
    wire.status((goal_id, GoalStatus.PENDING))                  # now it has: the cancel goes out
    assert wire.sent == [('goal', goal_id), ('cancel', goal_id)]
    wire.status((goal_id, GoalStatus.RECALLING))
    wire.result(goal_id, GoalStatus.RECALLED, 'recalled before it started')
    assert client.wait_ended(0.0)
    assert client.get_state() == GoalStatus.RECALLED
    assert client.get_result().message == 'recalled before it started'


def test_a_goal_cancelled_while_active_is_cancelled_at_once():
    wire = Wire()
    client = SimpleGoalClient(client=wire)
    client.send_goal(PirateGoal(name=1))
    goal_id = wire.sent[0][1]
    wire.status((goal_id, GoalStatus.ACTIVE))
    client.cancel_goal()
    assert wire.sent == [('goal', goal_id), ('cancel', goal_id)]
    wire.result(goal_id, GoalStatus.PREEMPTED, 'cancelled')
    assert client.wait_ended(0.0) and client.get_state() == GoalStatus.PREEMPTED
