"""Clamp state from what the robot senses, and the server state after every outcome.

After a cancel or an abort the robot may be partly or fully clamped;
the server must not say "Idle Unclamped" then. The classifier decides per
part from the bend angles (the guard rows of config/guards_<mm>.yaml) and
the springs (the ``clamp_state`` row); the server reports it after every
outcome, whatever the PAB meant to leave.
"""
import math

import pytest

from pirate.state import feed as feeds
from pirate.state.feed import RobotFeed, RobotView
from pirate.sequencer import clamp_state as cs
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import PABS
from pirate.sequencer.pabs.base import Pab, PabFailed
from pirate.sequencer.primitives import MotionPrimitives
from pirate.sequencer.server import ABORTED, PREEMPTED, SUCCEEDED, PirateServer

from fakes import command_arrays

BOOK = GuardBook(*load_files())
FRONT_FULL = dict(bend_i=-0.82, bend_ii=0.42)
REAR_FULL = dict(bend_iv=-0.82, bend_iii=0.42)
ON_WALL = dict(bend_i=241.1, bend_iv=241.1)      # outer springs at the clamp's torque, mNm
FRONT_PARTLY = dict(bend_i=-0.33, bend_ii=0.20)     # Table 6.5, partial unclamp
REAR_PARTLY = dict(bend_iv=-0.33, bend_iii=0.20)
FRONT_CUSTOM = dict(bend_i=-0.73, bend_ii=0.31)     # Table 5.3, not the full guard
POSES = {   # name: (angles, efforts, idle state)
    'clamped': (dict(FRONT_FULL, **REAR_FULL), ON_WALL, cs.IDLE_CLAMPED),
    'clamp angles, short of the wall': (dict(FRONT_FULL, **REAR_FULL), {},
                                        'Idle Partly Clamped (front partly clamped, rear partly clamped)'),
    'free': ({}, {}, cs.IDLE_UNCLAMPED),
    'rear clamped, front partly': (dict(FRONT_PARTLY, **REAR_FULL), ON_WALL,
                                   'Idle Partly Clamped (front partly clamped, rear full)'),
}


def angles(**joints):
    base = {n: 0.0 for n in ('front_tilt', 'bend_i', 'bend_ii', 'rotation', 'bend_iii', 'bend_iv')}
    base.update(joints)
    return base


@pytest.mark.parametrize('mm', [90, 110])
def test_free_and_full_per_diameter(mm):
    guards = BOOK.for_diameter(mm)
    closed = guards.pair('clamp', 'front')
    pose = angles(bend_i=closed.outer.guard - 0.01, bend_ii=closed.inner.guard + 0.01)
    assert cs.classify(guards, pose, dict(bend_i=241.1)) == cs.ClampState(cs.FULL, cs.FREE)
    assert cs.classify(guards, angles(), {}) == cs.ClampState(cs.FREE, cs.FREE)


#: What seq_mission's robot sensed right after Home said "unclamped" (fast fake,
#: under load): the rear's held inner bend had taken up its outer bend's closure
#: and stood 0.0036 rad past its 0.07 rad unclamp guard, no spring pressing.
AFTER_HOME = (dict(bend_i=-0.196, bend_ii=-0.020, bend_iii=0.0736, bend_iv=-0.1457),
              dict(bend_ii=240.1))


def test_a_part_settling_just_past_its_unclamp_guard_is_still_free():
    guards = BOOK.for_diameter(90)
    pose, efforts = AFTER_HOME
    assert not guards.pair('unclamp', 'rear').opened(angles(**pose))   # past the primitive's exact guard
    assert cs.idle_state(cs.classify(guards, angles(**pose), efforts)) == cs.IDLE_UNCLAMPED


#: What the twin's robot sensed 2 s after a 90 mm MITRE_BEND RIGHT at 15 mm/s
#: ended clamped sideways (bench/junction_turn_probe --side right --speed 15):
#: the front's Bend I had settled 0.002 rad back past its -0.60 rad guard,
#: its spring still on the wall; the server said "front partly clamped".
AFTER_TURN = (dict(front_tilt=-0.05, bend_i=-0.598, bend_ii=0.39, bend_iii=0.39, bend_iv=-0.78),
              dict(bend_i=242.0, bend_ii=-1.0, bend_iii=5.0, bend_iv=238.0), 0.019)


def test_a_clamp_settling_just_back_past_its_guard_with_its_spring_on_the_wall_is_still_clamped():
    guards = BOOK.for_diameter(90)
    pose, efforts, roll = AFTER_TURN
    assert not guards.pair('clamp_sideways', 'front').closed(angles(**pose))   # the primitive's exact guard
    assert cs.classify(guards, angles(**pose), efforts, roll) == (cs.FULL, cs.FULL)
    assert cs.classify_part(guards, 'front', angles(**pose), {}, roll) == cs.PARTLY   # no spring: not clamped


@pytest.mark.parametrize('mm', [90, 110])
def test_past_the_clamp_margin_is_not_clamped_even_pressing(mm):
    guards = BOOK.for_diameter(mm)
    full = guards.pair('clamp', 'rear')
    short = full.outer.guard + cs.clamp_margin_rad(guards) + 0.005
    pose = angles(bend_iv=short, bend_iii=full.inner.guard + 0.05)
    assert cs.classify_part(guards, 'rear', pose, ON_WALL) != cs.FULL
    within = angles(bend_iv=short - 0.01, bend_iii=full.inner.guard + 0.05)
    assert cs.classify_part(guards, 'rear', within, ON_WALL) == cs.FULL


@pytest.mark.parametrize('mm', [90, 110])
def test_past_the_free_margin_or_pressing_is_partly_clamped(mm):
    guards = BOOK.for_diameter(mm)
    rear = guards.pair('unclamp', 'rear')
    beyond = rear.inner.guard + cs.free_margin_rad(guards) + 0.005
    assert cs.classify_part(guards, 'rear', angles(bend_iii=beyond), {}) == cs.PARTLY
    pressing = {rear.inner.joint: -cs.spring_contact_mnm(guards) - 1.0}
    assert cs.classify_part(guards, 'rear', angles(), pressing) == cs.PARTLY


def test_a_90_mm_clamp_is_not_a_110_mm_clamp():
    pose = angles(**dict(FRONT_FULL, **REAR_FULL))
    assert cs.classify(BOOK.for_diameter(90), pose, ON_WALL) == (cs.FULL, cs.FULL)
    assert cs.classify(BOOK.for_diameter(110), pose, ON_WALL) == (cs.PARTLY, cs.PARTLY)


def test_custom_clamp_only_where_the_diameter_has_custom_guards():
    pose = angles(**FRONT_CUSTOM)
    assert cs.classify_part(BOOK.for_diameter(90), 'front', pose, ON_WALL) == cs.CUSTOM
    assert cs.classify_part(BOOK.for_diameter(110), 'front', pose, ON_WALL) == cs.PARTLY
    assert cs.classify_part(BOOK.for_diameter(90), 'front', pose, {}) == cs.PARTLY


def test_partly_between_open_and_clamped():
    guards = BOOK.for_diameter(90)
    assert cs.classify_part(guards, 'rear', angles(**REAR_PARTLY), {}) == cs.PARTLY


@pytest.mark.parametrize('bend,effort,expected', [
    ('bend_i', 100.0, cs.PARTLY),     # outer pushes toward the wall
    ('bend_ii', -100.0, cs.PARTLY),   # inner pushes toward the wall
    ('bend_i', -160.0, cs.FREE),      # unclamping against the straight stop
    ('bend_ii', 240.0, cs.FREE),
    ('bend_i', 30.0, cs.FREE),        # below the contact threshold
])
def test_open_angles_with_a_spring_pushing_toward_the_wall_are_not_free(bend, effort, expected):
    guards = BOOK.for_diameter(90)
    assert cs.spring_contact_mnm(guards) == 60.0
    assert cs.classify_part(guards, 'front', angles(), {bend: effort}) == expected


#: Recorded in the physics twin (straight_90 / straight_110 worlds, SimHarness,
#: 1 s of robot time after the event): bend angles (rad) and spring efforts
#: (mNm) of each part, and what the part is. "cancelled at the guard": Clamp
#: Straight cancelled as the rear outer bend reached its guard; the V stops
#: short of the wall while the inner spring pushes on the floor.
RECORDED = [   # (mm, part, angles, efforts, class)
    (90, 'rear', dict(bend_iv=-1.019, bend_iii=0.509), dict(bend_iv=241.1, bend_iii=0.0), cs.FULL),
    (90, 'front', dict(bend_i=-1.005, bend_ii=0.506), dict(bend_i=241.1, bend_ii=0.0), cs.FULL),
    (110, 'front', dict(bend_i=-1.586, bend_ii=0.793), dict(bend_i=241.1, bend_ii=0.0), cs.FULL),
    (90, 'rear', dict(bend_iv=-0.765, bend_iii=0.437), dict(bend_iv=-34.3, bend_iii=-193.7), cs.PARTLY),
    (90, 'rear', dict(bend_iv=-0.785, bend_iii=0.437), dict(bend_iv=-34.3, bend_iii=-193.7), cs.PARTLY),
    (110, 'rear', dict(bend_iv=-1.262, bend_iii=0.729), dict(bend_iv=-41.4, bend_iii=-191.6), cs.PARTLY),
    (90, 'front', dict(bend_i=0.048, bend_ii=-0.104), dict(bend_i=7.1, bend_ii=-13.1), cs.FREE),
    # the robot's weight on worm-held bends (efforts recorded with both bends
    # at PWM 0 after an unclamp) under clamp angles: no clamp, and not free
    (90, 'rear', dict(bend_iv=-0.85, bend_iii=0.40), dict(bend_iv=127.1, bend_iii=121.0), cs.PARTLY),
    (90, 'rear', dict(bend_iv=-0.123, bend_iii=0.061), dict(bend_iv=127.1, bend_iii=121.0), cs.PARTLY),
    (110, 'front', dict(bend_i=0.091, bend_ii=-0.189), dict(bend_i=6.1, bend_ii=-13.1), cs.FREE),
]


@pytest.mark.parametrize('mm,part,joints,efforts,expected', RECORDED)
def test_recorded_twin_values(mm, part, joints, efforts, expected):
    assert cs.classify_part(BOOK.for_diameter(mm), part, angles(**joints), efforts) == expected


def test_idle_state_names_each_part():
    assert cs.idle_state(cs.ClampState(cs.FULL, cs.FULL)) == cs.IDLE_CLAMPED
    assert cs.idle_state(cs.ClampState(cs.FREE, cs.FREE)) == cs.IDLE_UNCLAMPED
    text = cs.idle_state(cs.ClampState(cs.CUSTOM, cs.FREE))
    assert text.startswith(cs.IDLE_PARTLY) and 'front custom' in text and 'rear free' in text


# --- the server after every outcome -----------------------------------------

class Goal(object):
    def __init__(self, name, pipe_diameter=90):
        self.name, self.pipe_diameter = name, pipe_diameter
        self.distance, self.speed, self.option = 0.0, 0.0, 0


class Ends(Pab):
    """A PAB that ends as the test says, the robot posed before it ran."""
    name = 'Ends'
    ending = None

    def check(self, goal, view, guards):
        return None

    def run(self, ctx):
        if self.ending is not None:
            raise self.ending
        return 'done'


ENDINGS = {SUCCEEDED: None, PREEMPTED: feeds.Cancelled('cancel'), ABORTED: PabFailed('stuck')}


@pytest.mark.parametrize('status', sorted(ENDINGS))
@pytest.mark.parametrize('pose', sorted(POSES))
def test_server_state_after_each_outcome_is_the_sensed_one(monkeypatch, status, pose):
    joints, efforts, expected = POSES[pose]
    _, setpoint, control, limit = command_arrays()
    feed = RobotFeed(0.3, clock=lambda: 50.0)
    prims = MotionPrimitives(setpoint, control, limit, feed)
    server = PirateServer(prims, feed, BOOK, lambda: None)
    monkeypatch.setattr(Ends, 'ending', ENDINGS[status])
    monkeypatch.setitem(PABS, 7, ('ENDS', Ends))
    feed.push(RobotView(angles(**joints), math.pi / 2, 0.0, 0.0, 1.0, efforts))
    goal = Goal(7)
    assert server.reserve(goal) is None
    assert server.run(goal).status == status
    assert server.status() == expected


#: Twin, 90 mm, Clamp Sideways RIGHT ended (1 s later): on the wall short of
#: the upright guard, because lying on a side the V spans the chord.
SIDEWAYS_90 = (angles(bend_i=-0.621, bend_ii=0.348, bend_iii=0.350, bend_iv=-0.704),
               dict(bend_i=241.0, bend_ii=-5.0, bend_iii=5.0, bend_iv=238.0))


@pytest.mark.parametrize('roll, state', [(0.011, (cs.FULL, cs.FULL)), (math.pi - 0.02, (cs.FULL, cs.FULL)),
                                         (math.pi / 2, (cs.PARTLY, cs.CUSTOM))])   # upright: rear past Table 5.3
def test_a_clamp_on_a_side_is_full_only_lying_on_a_side(roll, state):
    pose, efforts = SIDEWAYS_90
    assert cs.classify(BOOK.for_diameter(90), pose, efforts, roll) == state
    assert cs.classify(BOOK.for_diameter(90), pose, {}, roll) == (cs.PARTLY, cs.PARTLY)   # short of the wall


#: Twin, 90 mm, Clamp Sideways LEFT from 150 deg (bench/pab_clamp_probe 90 150 left),
#: after "clamp front custom first" on main: the rotation (-0.445 rad) has
#: put the front on its side (its roll 3.152 rad) while the rear (IMU 2.707
#: rad) is not; the front V presses the wall at -0.638 rad, short of the
#: report's -0.69, the rear is clamped.
FRONT_ON_ITS_SIDE = (dict(bend_i=-0.638, bend_ii=0.410, rotation=-0.445, bend_iii=0.388, bend_iv=-0.839),
                     dict(bend_i=240.0, bend_ii=-241.0, bend_iii=1.0, bend_iv=241.0), 2.707)


def test_each_part_is_judged_by_its_own_roll():
    guards = BOOK.for_diameter(90)
    pose, efforts, imu = FRONT_ON_ITS_SIDE
    assert cs.part_roll('front', angles(**pose), imu) == pytest.approx(3.152)
    assert cs.part_roll('rear', angles(**pose), imu) == imu
    assert cs.classify(guards, angles(**pose), efforts, imu) == cs.ClampState(cs.FULL, cs.FULL)
    aligned = dict(pose, rotation=0.0)       # the same bends with the front at the rear's roll
    # 0.43 rad off the side: the chord still keeps the V from the upright
    # guards, so its full row is the side's (clamp_sideways within_rad 0.86,
    # derived): on the wall there, full
    assert cs.classify(guards, angles(**aligned), efforts, imu).front == cs.FULL
    # 0.9 rad off the side: the upright rows, the V short of the report's
    # custom -0.69 (measured 0.7 rad off the side): partly
    assert cs.classify(guards, angles(**aligned), efforts, math.pi - 0.9).front == cs.PARTLY


#: Twin, 110 mm T_JOINT LEFT entered through the run, cancelled while
#: steering and re-sent: the rear's roll had drifted to 2.94 rad, 0.2 off its side, its V
#: on the wall at the side's angles (the wall at -0.92 rad there).
REAR_DRIFTED_110 = (angles(bend_iii=0.42, bend_iv=-0.88), dict(bend_iii=2.0, bend_iv=240.0), 2.94)


def test_a_rear_drifted_past_the_nominal_band_of_its_side_still_reads_clamped():
    guards = BOOK.for_diameter(110)
    pose, efforts, imu = REAR_DRIFTED_110
    low, high = guards.region('nominal')
    assert abs(imu - math.pi) > (high - low) / 2             # outside the +-0.17 rad band
    assert cs.full_row(guards, imu) == 'clamp_sideways'
    assert cs.classify_part(guards, 'rear', pose, efforts, imu) == cs.FULL
    assert cs.classify_part(guards, 'rear', pose, {}, imu) == cs.PARTLY          # no spring: short of the wall
    assert cs.classify_part(guards, 'rear', pose, efforts, math.pi / 2) != cs.FULL   # upright: -1.25 not reached
