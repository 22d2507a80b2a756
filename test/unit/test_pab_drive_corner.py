"""Drive clamped half round a corner is refused before anything moves (pabs.drive, pabs.half_round).

A turn cancelled twice can leave both parts pressing their walls half round
the corner, which the server reads as Idle Clamped; a Drive there turned
the front part's wheels along the new pipe and the rear's along the old
one, stalled in 0.4 s and aborted naming an end cap or an obstacle.
Recorded in the twin: 90 mm mitre bend LEFT cancelled 31 robot s in, re-sent
and cancelled again 4 s in, 2 s of safe hold
(`python3 bench/junction_turn_resume --cancel-at 31 --cancel-again 4`).
"""
import math

import pytest

from pirate.msg import PirateGoal
from pirate.sequencer import clamp_state
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import codes, junction
from pirate.sequencer.pabs.base import Ended
from pirate.sequencer.pabs.drive import Drive
from pirate.state.feed import RobotView

BOOK = GuardBook(*load_files())
JOINTS = ('front_tilt', 'bend_i', 'bend_ii', 'rotation', 'bend_iii', 'bend_iv')
SPRINGS = ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv')
#: (angles rad in JOINTS order, springs mNm in SPRINGS order, roll rad, odometry mm)
TWICE_CANCELLED = ((0.17, -0.67, 0.69, 0.00, 1.61, -0.76), (224, -112, 154, 290), 3.12, 534.0)
#: Clamped sideways LEFT in the new pipe, driving on after the corner (same
#: twin, a turn cancelled driving into the new pipe 49 s in).
CLAMPED_LEFT = ((0.17, -0.69, 0.39, 0.00, 0.38, -0.76), (235, 4, 11, 217), 3.12, 0.0)


def view_of(recorded):
    angles, springs, roll, odometry_mm = recorded
    return RobotView(dict(zip(JOINTS, angles)), roll, odometry_mm, 0.0, 1.0, dict(zip(SPRINGS, springs)))


def drive_check(recorded, after=None, mm=90):
    goal = PirateGoal(name=codes.DRIVE, pipe_diameter=mm, distance=100.0, speed=50.0)
    pab = Drive.for_goal(goal)
    pab.follows(after)
    return pab.check(goal, view_of(recorded), BOOK.for_diameter(mm))


def test_the_twice_cancelled_turn_reads_clamped_so_only_drive_itself_can_refuse():
    guards = BOOK.for_diameter(90)
    assert clamp_state.sensed(guards, view_of(TWICE_CANCELLED)) == (clamp_state.FULL, clamp_state.FULL)


STOPPED_SWINGING = Ended('Taking Mitre bend', junction.SWINGING_MIDDLE, 534.0, 'preempted')


def test_drive_where_a_turn_stopped_half_round_its_corner_is_refused_with_the_way_out():
    reason = drive_check(TWICE_CANCELLED, STOPPED_SWINGING)
    assert reason is not None and 'Drive cannot start half round a corner toward the LEFT' in reason, reason
    assert 'the last goal, Taking Mitre bend, stopped swinging the middle round here' in reason
    assert 'Bend III 1.61 rad: the middle swinging round' in reason
    assert 're-send the turn toward the LEFT to finish it' in reason


def test_drive_with_the_middle_swung_past_swing_rad_is_refused_on_the_bends_alone():
    """A manager started again without the record: the bends still say so past swing_rad (1.65)."""
    angles, springs, roll, odometry_mm = TWICE_CANCELLED
    swung = (angles[:4] + (1.70,) + angles[5:], springs, roll, odometry_mm)
    assert 'Bend III 1.70 rad: the middle swinging round' in drive_check(swung)


def test_drive_from_the_same_pose_once_the_robot_has_moved_is_not_refused():
    """Bend III 1.61 alone (below swing_rad) does not refuse: the record is of where the robot was."""
    assert drive_check(TWICE_CANCELLED, STOPPED_SWINGING._replace(odometry_mm=400.0)) is None


@pytest.mark.parametrize('after', [None, Ended('Taking Mitre bend', 'straightening (Clamp Sideways)', 0.0,
                                               'succeeded')])
def test_drive_from_a_straight_pipe_clamp_is_not_refused(after):
    assert drive_check(CLAMPED_LEFT, after) is None


def test_a_bad_distance_is_still_refused_first():
    goal = PirateGoal(name=codes.DRIVE, pipe_diameter=90, distance=math.nan, speed=50.0)
    reason = Drive.for_goal(goal).check(goal, view_of(TWICE_CANCELLED), BOOK.for_diameter(90))
    assert 'drive distance nan mm' in reason
