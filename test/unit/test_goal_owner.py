"""Every goal has a living owner (pirate.manager.goal_owner and its ROS edge).

The policy decides from ping outcomes on an explicit clock; the pings run
against real XMLRPC servers on this host (no master); the monitor and the
manager's own goal callbacks run in-process against the Pirate Server over
the simulated robot (SimHarness), the owner's pings faked: a goal whose
owner stops answering ends preempted, naming it, and the robot stands still.
"""
import os
import socket
import threading
import time
import xmlrpc.server

import pytest
from actionlib_msgs.msg import GoalStatus

from pirate.manager import goal_owner, manager_node
from pirate.manager.goal_owner import ANSWERED, REFUSED, UNANSWERED, OwnerWatch, Ping
from pirate.manager.goal_owner_ros import OwnerMonitor, owner_of, ping_node
from pirate.robot.writers import OneWriter
from pirate.testing.harness import SimHarness

from test_faults import assert_hold_on_wire
from test_sequencer_sim import CLAMP_STRAIGHT, DRIVE, run_bounded

OWNER = '/mission_executive'
ALIVE = Ping(ANSWERED, 4242, '')
GONE = Ping(REFUSED, None, 'its XMLRPC server refused the connection: the process is gone')
SILENT = Ping(UNANSWERED, None, 'no answer within 0.20 s')
GOAL_END_BOUND_S = 30.0     # wall: a goal whose owner was lost ends long before this


# --- the policy ---------------------------------------------------------
def test_a_refused_connection_is_gone_at_once_naming_the_owner_and_why():
    watch = OwnerWatch(OWNER, 'goal-7', since_s=10.0)
    assert watch.heard(ALIVE, 10.1) is None
    reason = watch.heard(GONE, 10.2)
    assert OWNER in reason and 'goal-7' in reason and 'refused' in reason and 'safe hold' in reason


def test_an_unanswered_owner_is_gone_only_after_the_bound():
    watch = OwnerWatch(OWNER, 'g', since_s=0.0)
    assert watch.heard(ALIVE, 1.0) is None
    assert watch.heard(SILENT, 1.0 + goal_owner.UNANSWERED_S - 0.01) is None
    reason = watch.heard(SILENT, 1.0 + goal_owner.UNANSWERED_S)
    assert OWNER in reason and 'unanswered for 0.80 s' in reason and 'no answer within' in reason


def test_an_answer_restarts_the_count():
    watch = OwnerWatch(OWNER, 'g', since_s=0.0)
    assert watch.heard(SILENT, 0.7) is None
    assert watch.heard(ALIVE, 0.75) is None
    assert watch.heard(SILENT, 1.5) is None
    assert watch.heard(SILENT, 1.55) is not None


def test_acceptance_counts_as_the_last_sign_of_life():
    """A node the master never named: gone once unanswered for the bound from acceptance."""
    watch = OwnerWatch(OWNER, 'g', since_s=0.0)
    assert watch.heard(goal_owner.UNKNOWN, 0.7) is None
    assert 'not known to the master' in watch.heard(goal_owner.UNKNOWN, 0.8)


def test_another_process_answering_under_the_owner_name_is_not_the_owner():
    watch = OwnerWatch(OWNER, 'g', since_s=0.0)
    assert watch.heard(ALIVE, 0.2) is None
    reason = watch.heard(Ping(ANSWERED, 999, ''), 0.4)
    assert 'pid 999' in reason and 'pid 4242' in reason


def test_gone_stays_gone():
    watch = OwnerWatch(OWNER, 'g', since_s=0.0)
    reason = watch.heard(GONE, 0.1)
    assert watch.heard(ALIVE, 0.2) == reason


def test_the_managers_own_goals_and_unknown_senders_are_not_pinged():
    assert goal_owner.pinged(OWNER, '/pirate_manager')
    assert not goal_owner.pinged('/pirate_manager', '/pirate_manager')
    assert not goal_owner.pinged(None, '/pirate_manager')


@pytest.mark.parametrize('error, kind', [
    (ConnectionRefusedError(111, 'Connection refused'), REFUSED),
    (ConnectionResetError(104, 'Connection reset by peer'), REFUSED),
    (socket.timeout('timed out'), UNANSWERED),
    (OSError(113, 'No route to host'), UNANSWERED),
    (ValueError('bad reply'), UNANSWERED)])
def test_ping_failures(error, kind):
    assert goal_owner.failure(error, 0.2).kind == kind


def test_ping_answers():
    assert goal_owner.answer([1, '', 42]) == Ping(ANSWERED, 42, '')
    assert goal_owner.answer([-1, 'bad caller id', 0]).kind == UNANSWERED


# --- the pings, against XMLRPC servers on this host ---------------------
@pytest.fixture
def node_server():
    server = xmlrpc.server.SimpleXMLRPCServer(('127.0.0.1', 0), logRequests=False)
    server.register_function(lambda caller_id: [1, '', os.getpid()], 'getPid')
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield server, 'http://127.0.0.1:%d/' % server.server_address[1]
    server.shutdown()
    server.server_close()


def test_a_living_node_answers_with_its_pid(node_server):
    _server, uri = node_server
    assert ping_node('/pirate_manager', uri) == Ping(ANSWERED, os.getpid(), '')


def test_a_node_whose_process_ended_refuses(node_server):
    server, uri = node_server
    server.shutdown()
    server.server_close()
    assert ping_node('/pirate_manager', uri).kind == REFUSED


def test_a_hung_node_is_unanswered_within_the_ping_timeout():
    """Its socket still listens (the kernel accepts the connection) but nothing reads."""
    hung = socket.socket()
    hung.bind(('127.0.0.1', 0))
    hung.listen(5)
    try:
        start = time.monotonic()
        ping = ping_node('/pirate_manager', 'http://127.0.0.1:%d/' % hung.getsockname()[1], timeout_s=0.2)
        assert ping.kind == UNANSWERED and 'no answer within 0.20 s' in ping.why
        assert time.monotonic() - start < 5.0       # bounded by the timeout, not blocked
    finally:
        hung.close()


# --- the monitor ----------------------------------------------------------
class _Id(object):
    def __init__(self, text):
        self.id = text


class _ActionGoal(object):
    """The ActionGoal message as rospy delivers it: its connection header names the publisher."""

    def __init__(self, goal, owner):
        self.goal = goal
        self._connection_header = {'callerid': owner}


class Handle(object):
    """What the manager uses of actionlib's ServerGoalHandle."""

    def __init__(self, goal, goal_id, owner):
        self.goal = _ActionGoal(goal, owner)
        self._id = _Id(goal_id)
        self.status = GoalStatus.PENDING
        self.text = ''
        self.done = threading.Event()

    def get_goal(self):
        return self.goal.goal

    def get_goal_id(self):
        return self._id

    def get_goal_status(self):
        return self

    def set_accepted(self, _text=''):
        self.status = GoalStatus.ACTIVE

    def _end(self, status, text):
        self.status, self.text = status, text
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
        pass


class Owner(object):
    """A goal's owner seen through its pings: alive until :meth:`kill`."""

    def __init__(self):
        self.alive = True
        self.pings = 0
        self.lookups = []

    def lookup(self, _own_name, node):
        self.lookups.append(node)
        return 'http://owner:4711/'

    def ping(self, _own_name, _uri):
        self.pings += 1
        return ALIVE if self.alive else GONE


def test_owner_of_reads_the_goals_caller_id():
    assert owner_of(Handle(None, 'g', OWNER)) == OWNER
    assert owner_of(object()) is None


def test_the_monitor_reports_a_refusing_owner_once_and_looks_it_up_once():
    owner, gone = Owner(), []
    monitor = OwnerMonitor('/pirate_manager', lambda handle, reason: gone.append((handle, reason)),
                           lookup=owner.lookup, ping=owner.ping)
    handle = Handle(None, 'g1', OWNER)
    monitor.watch(handle)
    assert monitor.owner == OWNER
    goal = monitor._goal
    monitor.check(goal)
    owner.alive = False
    monitor.check(goal)
    monitor.check(goal)
    assert [h for h, _ in gone] == [handle] and OWNER in gone[0][1]
    assert owner.lookups == [OWNER]
    assert monitor.lost == gone[0][1] and monitor.owner is None


def test_the_monitor_does_not_ping_its_own_goals_nor_a_released_one():
    owner, gone = Owner(), []
    monitor = OwnerMonitor('/pirate_manager', lambda *args: gone.append(args), lookup=owner.lookup, ping=owner.ping)
    monitor.watch(Handle(None, 'panel', '/pirate_manager'))
    assert monitor.owner is None
    handle = Handle(None, 'g2', OWNER)
    monitor.watch(handle)
    goal = monitor._goal
    monitor.release(handle)
    owner.alive = False
    monitor.check(goal)
    assert gone == []


# --- the manager, in-process ------------------------------------------------
class _Diagnostics(object):
    def __init__(self):
        self.forced = 0

    def force_update(self):
        self.forced += 1


@pytest.fixture
def manager(monkeypatch):
    """pirate_manager's goal callbacks, worker and owner monitor over the simulated robot."""
    stop = threading.Event()
    errors = []
    monkeypatch.setattr(manager_node.rospy, 'is_shutdown', stop.is_set)
    monkeypatch.setattr(manager_node.rospy, 'logerr', lambda *args: errors.append(args[0] % args[1:]))
    with SimHarness() as sim:
        mgr = manager_node.PirateManager.__new__(manager_node.PirateManager)
        mgr.server, mgr.feed, mgr.prims = sim.server, sim.feed, sim.prims
        mgr._pending, mgr._queue, mgr._current = threading.Condition(), [], None
        mgr._writers = OneWriter('/pirate_manager')
        mgr._diagnostics = _Diagnostics()
        owner = Owner()
        mgr._owners = OwnerMonitor('/pirate_manager', mgr._owner_gone, lookup=owner.lookup, ping=owner.ping)
        sim.server._feedback = mgr._publish_feedback
        threads = [threading.Thread(target=mgr._worker, daemon=True),
                   threading.Thread(target=mgr._owners.run, args=(stop.is_set,), daemon=True)]
        for thread in threads:
            thread.start()
        yield mgr, sim, owner, errors
        stop.set()
        for thread in threads:
            thread.join(5.0)


def test_a_drive_whose_owner_dies_is_cancelled_into_the_hold(manager):
    mgr, sim, owner, errors = manager
    reason, outcome = run_bounded(sim, sim.goal(CLAMP_STRAIGHT))
    assert reason is None and outcome.status == 'succeeded', (reason, outcome)
    sim.pace = 2.0                  # robot s per wall s: the owner is judged on the wall clock
    handle = Handle(sim.goal(DRIVE, distance=3000.0, speed=150.0), 'drive-1', OWNER)
    mgr._on_goal(handle)
    assert handle.status == GoalStatus.ACTIVE
    start_mm = sim.travel_mm()
    assert sim.wait_robot(lambda: sim.travel_mm() - start_mm > 50.0, 10.0), 'the drive never moved'
    owner.alive = False
    assert handle.done.wait(GOAL_END_BOUND_S), 'the goal of a dead owner ran on'
    assert handle.status == GoalStatus.PREEMPTED, handle.text
    assert OWNER in handle.text and 'drive-1' in handle.text, handle.text
    assert errors and OWNER in errors[0] and mgr._diagnostics.forced == 1
    assert mgr._owners.lost and OWNER in mgr._owners.lost
    assert_hold_on_wire(sim)
    sim.pace = None
    sim.run_for(1.0)                # coast to a stop
    stopped_mm = sim.travel_mm()
    sim.run_for(1.0)
    assert abs(sim.travel_mm() - stopped_mm) < 1.0
    assert sim.travel_mm() - start_mm < 2000.0     # far short of the 3000 mm asked


def test_a_goal_whose_owner_lives_runs_to_its_end(manager):
    mgr, sim, owner, errors = manager
    reason, outcome = run_bounded(sim, sim.goal(CLAMP_STRAIGHT))
    assert reason is None and outcome.status == 'succeeded', (reason, outcome)
    sim.pace = 4.0
    handle = Handle(sim.goal(DRIVE, distance=200.0, speed=150.0), 'drive-2', OWNER)
    mgr._on_goal(handle)
    assert handle.done.wait(GOAL_END_BOUND_S)
    assert handle.status == GoalStatus.SUCCEEDED, handle.text
    assert owner.pings > 1 and errors == []


def test_diagnostics_say_the_lost_owner_as_an_error_until_the_next_goal():
    from pirate import health
    assert health.goal_owner(None, 'goal owner /x is gone (...)').level == health.ERROR
    assert OWNER in health.goal_owner(OWNER, None).message
    assert health.goal_owner(None, None).level == health.OK
