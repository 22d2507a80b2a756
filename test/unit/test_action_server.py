"""QuietActionServer (pirate.manager.action_server_ros): a cancel that arrives
before its goal, and cancels after it, log no actionlib error and the goal is
still recalled with a result. actionlib's own server, topics replaced, no master."""
import pytest
import rospy
from actionlib_msgs.msg import GoalID, GoalStatus

from pirate.msg import PirateAction, PirateActionGoal, PirateGoal
from pirate.manager.action_server_ros import QuietActionServer

GOAL_ID = 'storm-1'


class Topic(object):
    def __init__(self):
        self.sent = []

    def publish(self, msg):
        self.sent.append(msg)


@pytest.fixture
def server(monkeypatch):
    rospy.rostime.set_rostime_initialized(True)     # no master: ROS time is the wall clock
    errors = []
    monkeypatch.setattr(rospy, 'logerr', lambda text, *args: errors.append(text % args if args else text))
    cancelled, accepted = [], []
    action = QuietActionServer('pirate', PirateAction, accepted.append, cancelled.append, auto_start=False)
    action.status_pub, action.result_pub, action.feedback_pub = Topic(), Topic(), Topic()
    action.status_list_timeout = rospy.Duration(5.0)
    action.started = True
    return action, errors, cancelled, accepted


def goal(goal_id):
    return PirateActionGoal(goal_id=GoalID(id=goal_id), goal=PirateGoal(name=1))


@pytest.mark.parametrize('second_cancel', [GoalID(id=GOAL_ID), GoalID()])   # the same id again, a cancel-all
def test_a_cancel_before_its_goal_and_cancels_after_log_no_error(server, second_cancel):
    """Goal storms logged "uninitialized ServerGoalHandle" 362 and 1 136 times."""
    action, errors, cancelled, accepted = server
    action.internal_cancel_callback(GoalID(id=GOAL_ID))          # before its goal
    action.internal_cancel_callback(second_cancel)
    action.internal_goal_callback(goal(GOAL_ID))
    action.internal_cancel_callback(second_cancel)
    assert errors == []
    assert cancelled == [] and accepted == []                    # recalled by actionlib, never run
    results = [(r.status.goal_id.id, r.status.status) for r in action.result_pub.sent]
    assert results == [(GOAL_ID, GoalStatus.RECALLED)]
    assert [t.status.goal_id.id for t in action.status_list] == [GOAL_ID]


def test_a_cancel_of_a_running_goal_still_reaches_the_server(server):
    action, errors, cancelled, accepted = server
    action.internal_cancel_callback(GoalID(id='ghost'))          # a goal-less record beside it
    action.internal_goal_callback(goal(GOAL_ID))
    accepted[0].set_accepted()
    action.internal_cancel_callback(GoalID())                    # cancel-all
    assert [handle.get_goal_id().id for handle in cancelled] == [GOAL_ID]
    assert errors == []
