"""A cancel is never lost, one active goal always (manager_node).

The manager's own ``_on_goal`` / ``_on_cancel`` / ``_worker`` run in-process
against the real Pirate Server over the simulated robot (SimHarness), with
goal handles that follow actionlib's rules (one lock shared by the goal and
cancel callbacks and the status setters; a cancel reaches ``_on_cancel`` only
for a pending or active goal; ``publish_feedback`` lets other threads run, as
rospy's publish does). The robot stands still (its model does not
step), so no goal can end on its own before the primitive timeout: a goal
whose cancel was requested and that did not end preempted lost its cancel.

Two sender threads send a goal the moment the server reports idle (as the
panel's PabClient does); each accepted goal is cancelled at a random instant
0-2 ms after acceptance. So goals arrive in every phase of the previous
one's ending, including the window where the old worker cleared the handle
of a goal accepted after the server went idle (2 of 202 cancels lost over
ROS in the issue).
"""
import random
import threading
import time

import pytest
from actionlib_msgs.msg import GoalStatus

from pirate.robot.writers import OneWriter
from pirate.manager import manager_node
from pirate.manager.goal_owner_ros import OwnerMonitor
from pirate.testing.harness import SimHarness

CANCELS = 1000
SENDERS = 2
GOAL_END_BOUND_S = 30.0     # wall; a lost cancel ends by the primitive timeout (15 s robot, x50)
#: The robot paced on the wall clock: a goal outlives the 0-2 ms cancel instants (its 15 s timeout is 0.3 s wall).
ROBOT_S_PER_WALL_S = 50.0
ACTIONLIB_LOCK = threading.RLock()
#: An abort for lost robot state (a starved robot thread on a loaded machine)
#: ends the goal safely before its cancel is read; it is not a lost cancel.
LOST_STATE = 'no robot state'
ACTIVE = (GoalStatus.PENDING, GoalStatus.ACTIVE, GoalStatus.PREEMPTING, GoalStatus.RECALLING)


class _Id(object):
    def __init__(self, text):
        self.id = text


class _Status(object):
    def __init__(self, status):
        self.status = status


class Handle(object):
    """A ServerGoalHandle's status rules, under actionlib's one lock."""

    def __init__(self, goal, goal_id, registry):
        self._goal, self._id = goal, _Id(goal_id)
        self.status = GoalStatus.PENDING
        self.cancel_requested = False
        self.done = threading.Event()
        self._registry = registry

    def get_goal(self):
        return self._goal

    def get_goal_id(self):
        return self._id

    def get_goal_status(self):
        with ACTIONLIB_LOCK:
            return _Status(self.status)

    def set_accepted(self, _text=''):
        with ACTIONLIB_LOCK:
            self.status = GoalStatus.PREEMPTING if self.status == GoalStatus.RECALLING else GoalStatus.ACTIVE
            self._registry.check_one_active()

    def _end(self, status, text=''):
        self.text = text
        with ACTIONLIB_LOCK:
            self.status = status
        self.done.set()

    def set_rejected(self, _result=None, text=''):
        self._end(GoalStatus.REJECTED, text)

    def set_succeeded(self, _result=None, text=''):
        self._end(GoalStatus.SUCCEEDED, text)

    def set_canceled(self, _result=None, text=''):
        self._end(GoalStatus.PREEMPTED, text)

    def set_aborted(self, _result=None, text=''):
        self._end(GoalStatus.ABORTED, text)

    def publish_feedback(self, _feedback):
        time.sleep(0)       # the feedback message is built and serialised: the GIL moves on
        with ACTIONLIB_LOCK:
            self.feedbacks = getattr(self, 'feedbacks', 0) + 1
            time.sleep(0)   # rospy's publish hands the message to its thread: the GIL moves on


class Registry(object):
    """Every handle made, and the 'at most one active' invariant."""

    def __init__(self):
        self.handles = []
        self.violations = []

    def check_one_active(self):
        active = [h.get_goal_id().id for h in self.handles
                  if h.status in (GoalStatus.ACTIVE, GoalStatus.PREEMPTING)]
        if len(active) > 1:
            self.violations.append(active)


def _cancel(manager, handle):
    """What actionlib does on a cancel message for this goal id."""
    with ACTIONLIB_LOCK:
        if handle.status not in (GoalStatus.PENDING, GoalStatus.ACTIVE):
            return False
        handle.status = GoalStatus.RECALLING if handle.status == GoalStatus.PENDING else GoalStatus.PREEMPTING
        handle.cancel_requested = True
        manager._on_cancel(handle)
        return True


@pytest.fixture
def manager(monkeypatch):
    stop = threading.Event()
    monkeypatch.setattr(manager_node.rospy, 'is_shutdown', stop.is_set)
    monkeypatch.setattr(manager_node.rospy, 'logwarn', lambda *args: None)
    with SimHarness(pace=ROBOT_S_PER_WALL_S) as sim:
        sim.model.step = lambda dt: None        # the robot stands still: no goal ends by itself
        mgr = manager_node.PirateManager.__new__(manager_node.PirateManager)
        mgr.server, mgr.feed = sim.server, sim.feed
        mgr._pending, mgr._queue, mgr._current = threading.Condition(), [], None
        mgr._writers = OneWriter('/pirate_manager')
        mgr._owners = OwnerMonitor('/pirate_manager', mgr._owner_gone)     # these handles name no owner
        sim.server._feedback = mgr._publish_feedback      # wired as in PirateManager.__init__
        worker = threading.Thread(target=mgr._worker, daemon=True)
        worker.start()
        yield mgr, sim
        stop.set()
        worker.join(5.0)


def test_no_cancel_lost_at_random_instants_and_one_goal_active(manager):
    mgr, sim = manager
    registry = Registry()
    lock = threading.Lock()
    results = {'accepted': 0, 'lost': [], 'refused': 0}
    seq = [0]

    def sender(seed):
        rng = random.Random(seed)
        while True:
            with lock:
                if results['accepted'] >= CANCELS:
                    return
                seq[0] += 1
                handle = Handle(sim.goal(0), 'g%d' % seq[0], registry)
                registry.handles.append(handle)
            while mgr.server.active:      # send the moment the server reports idle, as
                time.sleep(0)             # the panel's PabClient and status pollers do
            with ACTIONLIB_LOCK:
                mgr._on_goal(handle)
            if handle.status == GoalStatus.REJECTED:
                with lock:
                    results['refused'] += 1
                threading.Event().wait(rng.uniform(0.0, 0.001))   # retry soon, at a random instant
                continue
            with lock:
                results['accepted'] += 1
            threading.Event().wait(rng.uniform(0.0, 0.002))   # the random instant, not a sync
            requested = _cancel(mgr, handle)
            if not handle.done.wait(GOAL_END_BOUND_S):
                results['lost'].append((handle.get_goal_id().id, 'never ended'))
            elif requested and handle.status != GoalStatus.PREEMPTED and LOST_STATE not in handle.text:
                results['lost'].append((handle.get_goal_id().id, handle.status, handle.text))

    threads = [threading.Thread(target=sender, args=(seed,)) for seed in range(SENDERS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(600.0)
    assert results['accepted'] >= CANCELS
    assert (len(results['lost']), len(registry.violations)) == (0, 0), (results['lost'][:5],
                                                                      registry.violations[:5])
    assert results['refused'] > 0, 'the second sender never overlapped: the test saw no race'
    assert all(h.done.is_set() for h in registry.handles)
