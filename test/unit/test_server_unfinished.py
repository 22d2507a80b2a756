"""What a goal leaves unfinished, and how it ended, outlive a restarted manager.

A turn cancelled once its rear came round leaves the server a record
(:class:`pirate.sequencer.pabs.junction.PastCorner`) that nothing sensed
can replace: before, a manager restarted (respawned after a crash, or by
the operator) forgot it, and the re-sent turn steered in a straight pipe
until its distance bound. The server now hands every change of the record
to ``keep_unfinished`` as plain data (the manager keeps it in its private
parameter ``~unfinished``, which outlives the node) and takes it back with
:meth:`PirateServer.restore_unfinished`, refusing data that is not one.
How the last goal ended (:data:`Ended`, told to the next PAB) is kept the
same way in ``~last_goal_ended``: before, Home from a manager restarted
where a turn stopped half round its corner was tried and blocked there.
"""
import collections
import math

import pytest

from pirate.robot.tables import JOINT_NAMES
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import PABS, codes
from pirate.sequencer.pabs import junction as jn
from pirate.sequencer.pabs.base import Ended, Pab, PabFailed
from pirate.sequencer.primitives import MotionPrimitives
from pirate.sequencer.server import ABORTED, SUCCEEDED, PirateServer
from pirate.state.feed import RobotFeed, RobotView

from fakes import command_arrays

BOOK = GuardBook(*load_files())
CODE = 7                                   # a code Pirate.action does not use
Goal = collections.namedtuple('Goal', 'name option distance speed pipe_diameter')
RECORD = jn.PastCorner('driving_in', 1182.0, 1332.0)


class LeavesARecord(Pab):
    """Aborts leaving RECORD unless it was handed one; then succeeds."""
    name = 'Leaves a record'
    record_from = classmethod(jn.TakeJunction.record_from.__func__)

    def __init__(self):
        self.carried = None

    def carry_on(self, record):
        self.carried = record

    def unfinished(self):
        return RECORD

    def run(self, ctx):
        if self.carried != RECORD:
            raise PabFailed('cancelled past the corner')
        return 'went on from %s' % (self.carried,)


def server(keep, log=None, keep_ended=None, view=None):
    """A server whose robot stands still (``view``, else straight at odometry
    1200 mm), each change of its record handed to ``keep``."""
    _, setpoint, control, limit = command_arrays()
    feed = RobotFeed(0.3, clock=lambda: 50.0)
    feed.push(view or RobotView(dict.fromkeys(JOINT_NAMES, 0.0), math.pi, 1200.0, 0.0, 50.0, {}))
    return PirateServer(MotionPrimitives(setpoint, control, limit, feed), feed, BOOK, lambda: None,
                        log=log, keep_unfinished=keep, keep_ended=keep_ended)


def run(srv, goal):
    assert srv.reserve(goal) is None
    return srv.run(goal)


@pytest.fixture
def leaves(monkeypatch):
    monkeypatch.setitem(PABS, CODE, ('LEAVES', LeavesARecord))
    return Goal(CODE, codes.LEFT, 800.0, 0.0, 90)


def test_a_restarted_server_takes_back_the_record_and_the_same_goal_goes_on_from_it(leaves):
    kept = []
    first = server(kept.append)
    assert run(first, leaves).status == ABORTED
    record = {'fact': 'driving_in', 'from_mm': 1182.0, 'to_mm': 1332.0, 'lead': 'front'}
    assert kept == [{'goal': [CODE, codes.LEFT, 90], 'record': record}]
    kept_after_restart = []
    second = server(kept_after_restart.append)
    assert second.restore_unfinished(kept[-1]) is None
    assert second.unfinished_data() == kept[-1]
    outcome = run(second, leaves)
    assert outcome.status == SUCCEEDED, outcome.message
    assert kept_after_restart == [None]      # done: the manager drops its parameter


def test_another_goal_after_a_restart_does_not_get_the_record_and_drops_it(leaves):
    kept = []
    srv = server(kept.append)
    assert srv.restore_unfinished({'goal': [CODE, codes.RIGHT, 90], 'record': RECORD._asdict()}) is None
    assert run(srv, leaves).status == ABORTED          # LEFT, not the RIGHT the record is of
    assert srv.unfinished_data()['goal'] == [CODE, codes.LEFT, 90]


@pytest.mark.parametrize('data, why', [
    ({}, "no 'goal'"),
    ({'goal': [codes.MITRE_BEND, codes.LEFT, 90]}, "no 'record'"),
    ({'goal': 'MITRE_BEND', 'record': RECORD._asdict()}, 'invalid literal'),
    ({'goal': [99, 1, 90], 'record': RECORD._asdict()}, 'no PAB with code 99'),
    ({'goal': [codes.DRIVE, 0, 90], 'record': RECORD._asdict()}, 'Drive keeps no record'),
    ({'goal': [codes.MITRE_BEND, codes.LEFT, 90], 'record': dict(RECORD._asdict(), fact='steering')},
     "fact 'steering' is none of"),
    ({'goal': [codes.MITRE_BEND, codes.LEFT, 90], 'record': dict(RECORD._asdict(), to_mm=float('nan'))},
     'is not one'),
    ({'goal': [codes.MITRE_BEND, codes.LEFT, 90], 'record': dict(RECORD._asdict(), from_mm=2000.0)},
     'is not one'),
    ({'goal': [codes.MITRE_BEND, codes.LEFT, 90], 'record': {'fact': 'driven_in', 'from_mm': 'x', 'to_mm': 1}},
     'could not convert'),
])
def test_data_that_is_not_a_record_is_refused_with_why_and_nothing_is_kept(data, why):
    srv = server(lambda data: None)
    srv.restore_unfinished({'goal': [codes.MITRE_BEND, codes.LEFT, 90], 'record': RECORD._asdict()})
    reason = srv.restore_unfinished(data)
    assert reason is not None and why in reason, reason
    assert srv.unfinished_data() is None


def test_a_turn_record_round_trips_through_plain_data():
    for fact in jn.RESUMED_TEXT:
        record = jn.PastCorner(fact, 10.0, 160.0)
        assert jn.TakeJunction.record_from(dict(record._asdict())) == record


class ParamServer(object):
    """The rospy calls the manager keeps its record with, over a dict."""

    def __init__(self, params=None, down=False):
        self.params, self.down, self.warned, self.said = dict(params or {}), down, [], []

    def _master(self):
        if self.down:
            raise OSError('connection refused')

    def set_param(self, name, value):
        self._master()
        self.params[name] = value

    def has_param(self, name):
        self._master()
        return name in self.params

    def get_param(self, name):
        return self.params[name]

    def delete_param(self, name):
        self._master()
        del self.params[name]

    def logwarn(self, text, *args):
        self.warned.append(text % args)

    def loginfo(self, text, *args):
        self.said.append(text % args)


@pytest.fixture
def node(monkeypatch):
    from pirate.manager import manager_node
    return manager_node, lambda fake: monkeypatch.setattr(manager_node, 'rospy', fake)


def test_the_manager_keeps_the_record_in_a_parameter_and_a_new_one_takes_it_back(node, leaves):
    manager_node, use = node
    params = ParamServer()
    use(params)
    first = server(manager_node._keep_unfinished)
    assert run(first, leaves).status == ABORTED
    assert params.params[manager_node.UNFINISHED_PARAM]['record']['fact'] == 'driving_in'
    second = server(manager_node._keep_unfinished)
    manager_node._restore_unfinished(second)
    assert params.said and not params.warned
    assert run(second, leaves).status == SUCCEEDED
    assert manager_node.UNFINISHED_PARAM not in params.params


def test_a_parameter_that_is_not_a_record_is_dropped_with_a_warning(node):
    manager_node, use = node
    params = ParamServer({manager_node.UNFINISHED_PARAM: {'goal': [codes.MITRE_BEND, codes.LEFT, 90]}})
    use(params)
    srv = server(manager_node._keep_unfinished)
    manager_node._restore_unfinished(srv)
    assert srv.unfinished_data() is None and manager_node.UNFINISHED_PARAM not in params.params
    assert len(params.warned) == 1 and "no 'record'" in params.warned[0]


def test_a_master_that_does_not_answer_costs_the_record_not_the_outcome(node, leaves):
    manager_node, use = node
    params, said = ParamServer(down=True), []
    use(params)
    srv = server(manager_node._keep_unfinished, said.append)
    outcome = run(srv, leaves)
    assert outcome.status == ABORTED and 'cancelled past the corner' in outcome.message
    assert srv.active is None and srv.reserve(leaves) is None          # the server ended the goal
    assert any('could not keep' in line and 'connection refused' in line for line in said), said


#: A 110 mm T-joint LEFT cancelled 35 robot s in, swinging the middle round
#: (test_pab_home_corner.T_JOINT_SWINGING_110): no bend says "corner", only
#: how the turn ended does.
SWINGING = RobotView(dict(zip(('front_tilt', 'bend_i', 'bend_ii', 'rotation', 'bend_iii', 'bend_iv'),
                              (0.08, 0.20, 1.12, -0.03, 0.68, -1.33)), rotation=0.0), 3.10, 420.0, 0.0, 50.0, {})
TURN_ENDED = {'pab': 'Taking T-joint', 'state': jn.SWINGING_MIDDLE, 'odometry_mm': 420.0, 'status': 'preempted',
              'junction_missing': False}
HOME = Goal(codes.HOME, codes.NONE, 0.0, 0.0, 110)


def test_a_restarted_server_still_refuses_home_where_the_turn_before_the_restart_stopped():
    before_restart = server(lambda data: None, view=SWINGING)
    assert before_restart.reserve(HOME) is None        # nothing told it how the turn ended: Home is tried
    restarted = server(lambda data: None, view=SWINGING)
    assert restarted.restore_ended(dict(TURN_ENDED)) is None
    reason = restarted.reserve(HOME)
    assert reason is not None and 'the last goal, Taking T-joint, stopped swinging the middle round here' in reason


def test_how_each_goal_ended_is_handed_over_and_a_restarted_server_tells_the_next_pab(leaves, monkeypatch):
    ended = []
    first = server(lambda data: None, keep_ended=ended.append)
    assert run(first, leaves).status == ABORTED
    assert ended == [{'pab': 'Leaves a record', 'state': '', 'odometry_mm': 1200.0, 'status': ABORTED,
                      'junction_missing': False}]
    told = []
    monkeypatch.setattr(LeavesARecord, 'follows', lambda self, after: told.append(after), raising=False)
    second = server(lambda data: None)
    assert second.restore_ended(ended[-1]) is None and second.ended_data() == ended[-1]
    assert second.reserve(leaves) is None
    assert told == [Ended('Leaves a record', '', 1200.0, ABORTED)]


@pytest.mark.parametrize('change, why', [
    ({'pab': None}, 'pab None is not the name of a PAB'),
    ({'pab': ''}, "pab '' is not the name of a PAB"),
    ({'state': 3}, 'state 3 is not a PAB state'),
    ({'status': 'lost'}, "status 'lost' is none of succeeded, aborted, preempted"),
    ({'odometry_mm': 'far'}, 'could not convert'),
    ({'junction_missing': 'no'}, "junction_missing 'no' is not true or false"),
])
def test_data_that_is_not_how_a_goal_ended_is_refused_with_why_and_nothing_is_kept(change, why):
    srv = server(lambda data: None)
    assert srv.restore_ended(dict(TURN_ENDED)) is None
    reason = srv.restore_ended(dict(TURN_ENDED, **change))
    assert reason is not None and why in reason, reason
    assert srv.ended_data() is None


@pytest.mark.parametrize('data, why', [({}, "no 'pab'"), ('Taking T-joint', 'string indices'),
                                       ({'pab': 'Taking T-joint', 'state': 'x'}, "no 'odometry_mm'")])
def test_a_record_missing_a_field_is_refused(data, why):
    reason = server(lambda data: None).restore_ended(data)
    assert reason is not None and why in reason, reason


def test_the_manager_keeps_how_the_goal_ended_and_a_new_one_refuses_home_in_the_corner(node):
    manager_node, use = node
    params = ParamServer({manager_node.ENDED_PARAM: dict(TURN_ENDED)})
    use(params)
    srv = server(lambda data: None, keep_ended=manager_node._keep_ended, view=SWINGING)
    manager_node._restore_ended(srv)
    assert params.said == ['kept from the last run of this node: the last goal, Taking T-joint, ended preempted '
                           'in swinging the middle round at odometry 420 mm'] and not params.warned
    assert 'half round a corner' in srv.reserve(HOME)
    params.params[manager_node.ENDED_PARAM] = dict(TURN_ENDED, odometry_mm='420')      # set by hand, a string
    manager_node._restore_ended(srv)
    assert params.said[-1].endswith('at odometry 420 mm') and srv.ended_data()['odometry_mm'] == 420.0
    params.params[manager_node.ENDED_PARAM] = {'pab': 'Taking T-joint'}
    manager_node._restore_ended(srv)
    assert len(params.warned) == 1 and "no 'state'" in params.warned[0]
    assert manager_node.ENDED_PARAM not in params.params and srv.reserve(HOME) is None
