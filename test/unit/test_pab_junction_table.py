"""Take T-joint / Take mitre bend: the one table, and every refusal.

- the table, built for either leading part (front first, rear first),
  prints, every state is reachable, and exhaustively over its
  facts at most one transition fires per state, exactly one when the
  facts agree with what the state's action just did; the rear-first table
  is the front-first one with the parts swapped;
- a negative search distance takes a junction rear first from the clamp
  the way in left, and a direction not taken rear first says why;
- the facts of a T-joint taken straight on walk the report's steps;
- each goal the PAB cannot run is refused at once with its reason;
- a turn re-sent after a cancel resumes at the step that continues it from
  what the robot senses (signatures read in the twin: bench/junction_turn_resume
  --trace), exhaustively never restarts a turn in a corner nor resumes one
  toward the other side, and what it cannot resume from is refused with why.
"""
import collections
import itertools
import math

import pytest

from pirate.state.feed import RobotView
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import PABS, codes
from pirate.sequencer.pabs import junction as jn
from pirate.sequencer.pabs import junction_table as table
from pirate.sequencer.pabs.base import END, PabFailed
from pirate.sequencer.server import PabContext
from fakes import WithoutJunctionKey

BOOK = GuardBook(*load_files())
ALL_FACTS = [jn.Facts(*values) for values in itertools.product((True, False), repeat=len(jn.Facts._fields))]

def in_a_corner(f):
    return f.lead_round or f.corner_opening or f.middle_round or f.middle_swung or f.trail_round


def past_the_corner(f):
    return f.trail_through or f.driving_in or f.driven_in


#: What each state's action guarantees about the facts read right after it, by
#: the state's template (junction_table.STATES: the same whichever part leads).
GUARANTEES = {
    # from its start, straight or within the nominal band (what check() always accepted); the resumes below
    table.CHANGE_MODES: lambda f: f.lead and f.trail and (f.straight or f.toward) and not in_a_corner(f)
    and not past_the_corner(f),
    table.RE_ADJUSTING: lambda f: f.lead and f.trail and f.straight and not in_a_corner(f)
    and not past_the_corner(f),      # Clamp Straight / Sideways ended straight, or raised
    table.SEARCHING: lambda f: f.found and not f.turn,  # else it raised JunctionMissing
    table.STOPPING: lambda f: f.found and not f.turn,
    table.LIFTING_LEAD: lambda f: f.turn and not f.found,
    table.UNCLAMPING_LEAD: lambda f: (f.found or f.turn) and not f.lead,
    table.CROSSING_LEAD: lambda f: f.found and not f.lead and not f.turn,
    table.STEERING_LEAD: lambda f: f.turn and f.found and not f.lead,    # else JunctionMissing
    table.CLAMPING_LEAD_AT_CORNER: lambda f: f.turn and f.found,
    table.SWINGING_MIDDLE: lambda f: f.turn and f.found,
    table.BRINGING_TRAIL: lambda f: f.turn and f.found and not f.trail,
    table.CLAMPING_LEAD: lambda f: f.found and f.lead,
    # lying on a side the trailing part crosses pressing lightly, so it may still read clamped
    table.UNCLAMPING_TRAIL: lambda f: f.found and f.lead and not f.turn,
    table.CROSSING_TRAIL: lambda f: f.found and f.lead and not f.turn,
    table.CLAMPING_TRAIL: lambda f: f.found and f.trail and (f.lead or f.turn),
    table.DRIVING_IN: lambda f: f.turn and f.found and f.lead and f.trail,
    table.STRAIGHTENING: lambda f: f.found and f.lead and f.trail and f.straight,
}
#: Each table's states -> their guarantee.
POSTCONDITIONS = {lead: {table.state(template, lead): guarantee for template, guarantee in GUARANTEES.items()
                         if template != table.LIFTING_LEAD or lead in table.TILTS}
                  for lead in table.LEADS}
POSTCONDITION = POSTCONDITIONS['front']


@pytest.mark.parametrize('lead', sorted(table.LEADS))
def test_the_table_prints_every_transition(lead):
    machine = table.MACHINES[lead]
    printed = machine.table()
    assert printed.splitlines()[0].split() == ['state', 'next', 'state', 'guard']
    assert len(printed.splitlines()) == len(machine.transitions) + 1
    assert set(machine.states) == set(POSTCONDITIONS[lead]) | {END}


@pytest.mark.parametrize('lead, state', [(lead, state) for lead in sorted(table.LEADS)
                                         for state in sorted(POSTCONDITIONS[lead])])
def test_at_most_one_transition_and_one_where_the_action_succeeded(lead, state):
    machine = table.MACHINES[lead]
    for facts in ALL_FACTS:
        fired = [t for t in machine.exits(state) if t.guard.test(facts)]
        assert len(fired) <= 1, (state, facts)
        if POSTCONDITIONS[lead][state](facts):
            assert len(fired) == 1, (state, facts)


def test_the_rear_first_table_is_the_front_first_one_with_the_parts_swapped():
    """The same rows, guards tested alike, exhaustively; the states named
    for the part that leads; no lifting where the leading module has no tilt."""
    front, rear = table.MACHINES['front'], table.MACHINES['rear']
    renamed = {table.state(t, 'front'): table.state(t, 'rear') for t in table.STATES}
    opened = lambda target: table.UNCLAMPING_FRONT if target == table.LIFTING_FRONT else target  # noqa: E731
    rows = [(renamed[t.source], renamed.get(opened(t.target), t.target), t.guard) for t in front.transitions
            if t.source != table.LIFTING_FRONT]
    assert [(s, d) for s, d, _ in rows] == [(t.source, t.target) for t in rear.transitions]
    for (_, _, guard), t in zip(rows, rear.transitions):
        assert all(guard.test(facts) == t.guard.test(facts) for facts in ALL_FACTS), t
    assert 'front clamped' in rear.transitions[1].guard.text and 'rear clamped' in rear.transitions[1].guard.text


def test_a_clamp_that_does_not_hold_ends_the_pab():
    with pytest.raises(PabFailed):
        jn.MACHINE.next(jn.CLAMPING_REAR, jn.Facts(found=True, lead=True, trail=False, straight=True, turn=False))


def test_straight_through_a_t_joint_walks_the_reports_steps():
    """Report 4.7.4: detect, unclamp front, re-clamp front, the rear the same way."""
    facts = jn.Facts(found=False, lead=True, trail=True, straight=True, turn=False)
    after = {jn.SEARCHING: dict(found=True), jn.UNCLAMPING_FRONT: dict(lead=False),
             jn.CLAMPING_FRONT: dict(lead=True), jn.UNCLAMPING_REAR: dict(trail=False),
             jn.CLAMPING_REAR: dict(trail=True)}
    state, walked = jn.MACHINE.initial, []
    while state != END:
        walked.append(state)
        facts = facts._replace(**after.get(state, {}))
        state = jn.MACHINE.next(state, facts)
    assert walked == [jn.CHANGE_MODES, jn.SEARCHING, jn.STOPPING, jn.UNCLAMPING_FRONT, jn.CROSSING_FRONT,
                      jn.CLAMPING_FRONT, jn.UNCLAMPING_REAR, jn.CROSSING_REAR, jn.CLAMPING_REAR]


def test_clamped_past_the_junction_but_rolled_out_of_straight_re_adjusts():
    rolled = jn.Facts(found=True, lead=True, trail=True, straight=False, turn=False)
    assert jn.MACHINE.next(jn.CLAMPING_REAR, rolled) == jn.STRAIGHTENING
    assert jn.MACHINE.next(jn.STRAIGHTENING, rolled._replace(straight=True)) == END


def test_a_turn_steers_the_front_in_brings_the_rear_and_straightens():
    """Report 4.7.4 for a turn: the front part into the new pipe and clamped, then
    the rear part through, then the robot clamped in the new pipe."""
    facts = jn.Facts(found=False, lead=True, trail=True, straight=True, turn=True)
    after = {jn.UNCLAMPING_FRONT: dict(lead=False), jn.STEERING_FRONT: dict(found=True),
             jn.BRINGING_REAR: dict(trail=False), jn.CLAMPING_REAR: dict(trail=True),
             jn.CLAMPING_FRONT: dict(lead=True)}
    state, walked = jn.MACHINE.initial, []
    while state != END:
        walked.append(state)
        facts = facts._replace(**after.get(state, {}))
        state = jn.MACHINE.next(state, facts)
    assert walked == [jn.CHANGE_MODES, jn.LIFTING_FRONT, jn.UNCLAMPING_FRONT, jn.STEERING_FRONT,
                      jn.CLAMPING_AT_CORNER, jn.SWINGING_MIDDLE, jn.BRINGING_REAR, jn.CLAMPING_REAR,
                      jn.CLAMPING_FRONT, jn.DRIVING_IN, jn.STRAIGHTENING]


@pytest.mark.parametrize('turn, then', [(True, jn.LIFTING_FRONT), (False, jn.SEARCHING)])
def test_a_junction_from_a_clamp_rolled_out_of_straight_re_adjusts_it_first(turn, then):
    """Within the nominal band of its clamp: Clamp Sideways' / Straight's
    re-adjust, then the turn or the search from its start."""
    rolled = jn.Facts(found=False, lead=True, trail=True, straight=False, turn=turn, toward=True)
    assert jn.MACHINE.next(jn.CHANGE_MODES, rolled) == jn.RE_ADJUSTING
    assert jn.MACHINE.next(jn.RE_ADJUSTING, rolled._replace(straight=True)) == then
    with pytest.raises(PabFailed):          # a re-adjust that did not straighten ends the PAB
        jn.MACHINE.next(jn.RE_ADJUSTING, rolled)


# --- refusals ------------------------------------------------------------------
Goal = collections.namedtuple('Goal', 'name option distance speed pipe_diameter')
CLAMPED = dict(bend_i=-1.0, bend_ii=0.5, bend_iii=0.5, bend_iv=-1.0, rotation=0.0, front_tilt=0.44)   # 90 mm, twin
ON_WALL = dict(bend_i=241.0, bend_iv=241.0)


SIDEWAYS_LEFT = dict(CLAMPED, bend_i=-0.65, bend_ii=0.33, bend_iii=0.33, bend_iv=-0.65)


def view(orientation=math.pi / 2, angles=CLAMPED, efforts=ON_WALL):
    return RobotView(dict(angles), orientation, 0.0, 0.0, 1.0, dict(efforts))


def check(name, option, distance=0.0, speed=0.0, robot=None, mm=90):
    goal = Goal(name, option, distance, speed, mm)
    return PABS[name][1].for_goal(goal).check(goal, robot or view(), BOOK.for_diameter(mm))


@pytest.mark.parametrize('name, option, needle', [
    (codes.MITRE_BEND, codes.STRAIGHT, 'a mitre bend is taken LEFT / RIGHT / UP / DOWN, not STRAIGHT'),
    (codes.MITRE_BEND, codes.NONE, 'not NONE'),
    (codes.T_JOINT, codes.UP, 'a T-joint is taken LEFT / RIGHT / STRAIGHT, not UP'),
    (codes.T_JOINT, codes.DOWN, 'not DOWN'),
    (codes.T_JOINT, codes.NONE, 'not NONE'),
    (codes.T_JOINT, 9, 'not 9'),
])
def test_a_direction_the_junction_cannot_have_is_refused(name, option, needle):
    assert needle in check(name, option)


@pytest.mark.parametrize('mm', [90, 110])
@pytest.mark.parametrize('option, why', [(codes.UP, 'one V alone does not hold the robot'),
                                         (codes.DOWN, 'the front tilt stops at -0.1 rad and no clamp holds the '
                                                      'robot upside down')])
def test_turns_not_built_are_refused_as_not_yet_taken_with_the_reason(option, why, mm):
    reason = check(codes.MITRE_BEND, option, distance=800.0, mm=mm)       # clamped straight, as they would start
    assert 'not yet taken by this PAB' in reason and why in reason


def test_every_direction_a_junction_can_have_is_taken_or_says_why_not():
    for kind, _, _, options in jn.JUNCTIONS.values():
        for direction, _ in options.values():
            assert (kind, direction) in jn.TAKEN or direction in jn.NOT_TAKEN, (kind, direction)


def test_every_direction_taken_front_first_is_taken_rear_first_or_says_why_not():
    for kind, direction in jn.TAKEN:
        assert (kind, direction) in jn.TAKEN_REAR_FIRST or (kind, direction) in jn.NOT_TAKEN_REAR_FIRST
    assert jn.TAKEN_REAR_FIRST <= jn.TAKEN


@pytest.mark.parametrize('name, option, orientation, angles', [
    (codes.MITRE_BEND, codes.LEFT, math.pi, SIDEWAYS_LEFT), (codes.MITRE_BEND, codes.RIGHT, 0.0, SIDEWAYS_LEFT),
    (codes.T_JOINT, codes.STRAIGHT, math.pi / 2, CLAMPED)])
def test_a_junction_taken_rear_first_is_accepted_from_the_clamp_the_way_in_left(name, option, orientation, angles):
    """A negative search distance: the rear leads, from the same clamp as front first (90 mm)."""
    mm = 90
    robot = view(orientation, angles=angles)
    assert check(name, option, distance=-800.0, robot=robot, mm=mm) is None
    pab = PABS[name][1].for_goal(Goal(name, option, -800.0, 0.0, mm))
    assert pab.lead.part == 'rear' and pab.machine is table.MACHINES['rear']
    first = table.first_step(pab.sensed_facts(BOOK.for_diameter(mm), robot), 'rear')
    assert first == (table.state(table.UNCLAMPING_LEAD, 'rear') if option != codes.STRAIGHT else jn.SEARCHING)


@pytest.mark.parametrize('option, orientation', [(codes.LEFT, math.pi), (codes.RIGHT, 0.0)])
def test_a_t_joint_turn_rear_first_is_refused_with_why(option, orientation):
    reason = check(codes.T_JOINT, option, distance=-800.0, robot=view(orientation, angles=SIDEWAYS_LEFT))
    assert 'rear first is not yet taken by this PAB' in reason and 'the rear module has no tilt' in reason
    assert check(codes.T_JOINT, option, distance=800.0, robot=view(orientation, angles=SIDEWAYS_LEFT)) is None


@pytest.mark.parametrize('name', [codes.MITRE_BEND, codes.T_JOINT])
@pytest.mark.parametrize('option, orientation', [(codes.LEFT, math.pi), (codes.RIGHT, 0.0)])
def test_a_turn_is_taken_clamped_sideways_toward_it(name, option, orientation):
    clamped_sideways = view(orientation, angles=dict(CLAMPED, bend_i=-0.65, bend_ii=0.33, bend_iii=0.33, bend_iv=-0.65))
    assert check(name, option, distance=800.0, robot=clamped_sideways) is None
    other_side = view(math.pi - orientation, angles=dict(CLAMPED, bend_i=-0.65, bend_ii=0.33, bend_iii=0.33,
                                                         bend_iv=-0.65))
    assert 'starts clamped sideways %s' % codes.OPTION_NAMES[option] in check(name, option, robot=other_side)
    assert 'starts clamped sideways' in check(name, option, robot=view())       # upright


@pytest.mark.parametrize('offset, first', [(0.10, jn.RE_ADJUSTING), (-0.10, jn.RE_ADJUSTING), (0.03, jn.LIFTING_FRONT),
                                           (0.25, None)])
@pytest.mark.parametrize('option, orientation', [(codes.LEFT, math.pi), (codes.RIGHT, 0.0)])
def test_a_turn_from_a_clamp_a_drive_rolled_re_adjusts_it_within_the_nominal_band(option, orientation, offset,
                                                                                     first):
    """0.10 rad off (a 1.5 m drive in the twin): out of the straight band
    (+-0.05), within the nominal one (+-0.17), re-adjusted first; 0.25 off,
    refused with Clamp Sideways first."""
    robot = view(orientation + offset, angles=dict(CLAMPED, bend_i=-0.65, bend_ii=0.33, bend_iii=0.33, bend_iv=-0.65))
    assert first_step(codes.MITRE_BEND, option, robot) == first
    reason = check(codes.MITRE_BEND, option, distance=800.0, robot=robot)
    if first is None:
        assert 'Clamp Sideways %s first' % codes.OPTION_NAMES[option] in reason
    else:
        assert reason is None


@pytest.mark.parametrize('name', [codes.MITRE_BEND, codes.T_JOINT])
@pytest.mark.parametrize('option, orientation', [(codes.LEFT, math.pi), (codes.RIGHT, 0.0)])
def test_a_turn_in_110_mm_is_taken_clamped_sideways_toward_it(name, option, orientation):
    sideways_110 = dict(CLAMPED, bend_i=-0.9, bend_ii=0.45, bend_iii=0.45, bend_iv=-0.9)
    assert check(name, option, distance=800.0, robot=view(orientation, sideways_110), mm=110) is None


class _NoTurnRows(object):
    """A diameter's guards without the turn rows (a pipe nobody derived them for)."""

    def __init__(self, guards):
        self._guards = guards

    def has(self, kind):
        return kind != 'turn' and self._guards.has(kind)

    def __getattr__(self, name):
        return getattr(self._guards, name)


def test_a_turn_in_a_pipe_without_turn_rows_is_refused():
    goal = Goal(codes.MITRE_BEND, codes.LEFT, 800.0, 0.0, 110)
    sideways_110 = dict(CLAMPED, bend_i=-0.9, bend_ii=0.45, bend_iii=0.45, bend_iv=-0.9)
    reason = PABS[codes.MITRE_BEND][1].for_goal(goal).check(goal, view(math.pi, sideways_110),
                                                           _NoTurnRows(BOOK.for_diameter(110)))
    assert 'no turn guards for a 110 mm pipe' in reason


@pytest.mark.parametrize('distance', [-2001.0, 2001.0, float('nan'), float('inf')])
def test_a_search_distance_out_of_range_is_refused(distance):
    assert 'search distance' in check(codes.T_JOINT, codes.STRAIGHT, distance=distance)


@pytest.mark.parametrize('speed', [-20.0, 171.0, 0.1])
def test_a_speed_the_wheels_cannot_drive_is_refused(speed):
    assert 'drive speed' in check(codes.T_JOINT, codes.STRAIGHT, speed=speed)


@pytest.mark.parametrize('robot, needle', [
    (view(angles=dict(CLAMPED, bend_i=-0.1, bend_ii=0.02), efforts={}), 'front free'),
    (view(efforts={}), 'Idle Partly Clamped'),                     # clamp angles, nothing on the wall
    (view(orientation=1.0), 'at 1.00 rad'),                        # clamped, but not straight nor on a side
])
def test_the_robot_must_start_clamped(robot, needle):
    reason = check(codes.T_JOINT, codes.STRAIGHT, robot=robot)
    assert 'starts clamped straight' in reason and needle in reason
    assert reason.endswith('; Clamp Straight first'), reason            # the way on


UPRIGHT = {90: CLAMPED, 110: dict(CLAMPED, bend_i=-1.3, bend_ii=0.7, bend_iii=0.7, bend_iv=-1.3)}


@pytest.mark.parametrize('mm', [90, 110])
def test_straight_on_through_a_t_joint_clamped_straight_is_accepted(mm):
    assert check(codes.T_JOINT, codes.STRAIGHT, distance=800.0, robot=view(angles=UPRIGHT[mm]), mm=mm) is None


SIDEWAYS_ROW = 'straight_sideways_speed_min'


def check_without_sideways_row(name, option, robot, mm):
    """``check`` in a diameter whose guards do not take straight on lying on a side (no row)."""
    goal = Goal(name, option, 0.0, 0.0, mm)
    return PABS[name][1].for_goal(goal).check(goal, robot, WithoutJunctionKey(BOOK.for_diameter(mm), SIDEWAYS_ROW))


@pytest.mark.parametrize('orientation, mm, clamp', [(math.pi, 90, 'Clamp Sideways LEFT'),
                                                   (0.0, 90, 'Clamp Sideways RIGHT'),
                                                   (math.pi, 110, 'Clamp Sideways LEFT'),
                                                   (0.0, 110, 'Clamp Sideways RIGHT'),
                                                   (math.pi / 2, 90, 'Clamp Straight')])
def test_straight_on_refused_partly_clamped_names_the_clamp_to_send_first(orientation, mm, clamp):
    """The clamp it lies in, where straight on is taken from it (on a side: where the guards have the row)."""
    angles = SIDEWAYS[mm] if orientation != math.pi / 2 else UPRIGHT[mm]
    partly = view(orientation, angles=dict(angles, bend_iii=0.1, bend_iv=-0.2), efforts=dict(bend_i=241.0))
    reason = check(codes.T_JOINT, codes.STRAIGHT, robot=partly, mm=mm)
    assert reason.endswith('; %s first' % clamp), reason
    if clamp != 'Clamp Straight':        # without the row the way on is upright
        reason = check_without_sideways_row(codes.T_JOINT, codes.STRAIGHT, partly, mm)
        assert reason.endswith('; Clamp Straight first'), reason


@pytest.mark.parametrize('offset, first', [(0.10, jn.RE_ADJUSTING), (-0.10, jn.RE_ADJUSTING), (0.03, jn.SEARCHING),
                                           (0.25, None)])
def test_straight_on_from_a_clamp_a_drive_rolled_re_adjusts_it_within_the_nominal_band(offset, first):
    """Upright 0.10 rad off: out of the straight band, within the nominal
    one, re-adjusted first; 0.25 off, refused (neither straight nor on a side)."""
    robot = view(math.pi / 2 + offset)
    reason = check(codes.T_JOINT, codes.STRAIGHT, distance=800.0, robot=robot)
    if first is None:
        assert 'starts clamped straight' in reason
    else:
        assert reason is None and first_step(codes.T_JOINT, codes.STRAIGHT, robot) == first


SIDEWAYS = {90: SIDEWAYS_LEFT, 110: dict(CLAMPED, bend_i=-0.9, bend_ii=0.45, bend_iii=0.45, bend_iv=-0.9)}


@pytest.mark.parametrize('orientation, mm', [(0.0, 90), (math.pi, 90), (math.pi / 2, 90), (0.0, 110), (math.pi, 110),
                                              (math.pi / 2, 110)])
def test_straight_on_starts_from_the_clamp_it_holds_and_ends_in_it(orientation, mm):
    """A T-joint open to a side is gone straight through lying toward it
    (junctions.FACING_OPEN_SIDE): where the guards take it (90 and 110 mm), accepted clamped
    straight or sideways, and the machine's "straight" is judged around the
    clamp held at the start, the one the crossing ends in (not upright for a
    robot on a side)."""
    robot = view(orientation, angles=UPRIGHT[mm] if orientation == math.pi / 2 else SIDEWAYS[mm])
    assert check(codes.T_JOINT, codes.STRAIGHT, distance=800.0, robot=robot, mm=mm) is None
    pab = PABS[codes.T_JOINT][1].for_goal(Goal(codes.T_JOINT, codes.STRAIGHT, 800.0, 0.0, mm))
    assert pab.sensed_facts(BOOK.for_diameter(mm), robot).straight
    rolled_upright = view(math.pi / 2 if orientation != math.pi / 2 else 0.0, angles=robot.angles)
    assert not pab.sensed_facts(BOOK.for_diameter(mm), rolled_upright).straight
    assert pab._target() == orientation


@pytest.mark.parametrize('mm', [90, 110])
@pytest.mark.parametrize('orientation', [0.0, math.pi])
def test_straight_on_lying_on_a_side_without_its_row_is_refused_naming_the_way_past(orientation, mm):
    """A diameter whose guards have no straight_sideways_speed_min (not measured) refuses it."""
    reason = check_without_sideways_row(codes.T_JOINT, codes.STRAIGHT, view(orientation, angles=SIDEWAYS[mm]), mm)
    assert 'not taken in a %d mm pipe' % mm in reason and 'not measured in the twin' in reason, reason
    assert 'Clamp Straight and Drive instead' in reason                  # the way past (junctions.driven_past)
    assert check_without_sideways_row(codes.T_JOINT, codes.STRAIGHT, view(angles=UPRIGHT[mm]), mm) is None


@pytest.mark.parametrize('mm', [90, 110])
@pytest.mark.parametrize('orientation', [0.0, math.pi])
def test_straight_on_lying_on_a_side_is_refused_slower_than_its_row(orientation, mm):
    """90 and 110 mm take it from 50 mm/s (config/guards_<mm>.yaml straight_sideways_speed_min)."""
    robot = view(orientation, angles=SIDEWAYS[mm])
    assert 'needs at least 50 mm/s' in check(codes.T_JOINT, codes.STRAIGHT, speed=35.0, robot=robot, mm=mm)
    assert check(codes.T_JOINT, codes.STRAIGHT, speed=50.0, robot=robot, mm=mm) is None
    assert check(codes.T_JOINT, codes.STRAIGHT, speed=0.0, robot=robot, mm=mm) is None     # the row's search speed, 50
    assert check(codes.T_JOINT, codes.STRAIGHT, speed=25.0, robot=view(angles=UPRIGHT[mm]), mm=mm) is None


# --- a turn's speed ------------------------------------------------------------
#: mm -> the turn row's range (mm/s), measured in the twin (config/guards_<mm>.yaml).
TURN_SPEEDS = {90: (15, 25), 110: (20, 25)}


@pytest.mark.parametrize('mm, speed', [(90, 0.0), (90, 15.0), (90, 22.5), (90, 25.0), (110, 0.0), (110, 20.0),
                                       (110, 25.0)])
@pytest.mark.parametrize('name', [codes.MITRE_BEND, codes.T_JOINT])
def test_a_turn_takes_a_speed_within_its_rows_range(name, mm, speed):
    assert check(name, codes.LEFT, distance=800.0, speed=speed, robot=view(math.pi, SIDEWAYS[mm]), mm=mm) is None


@pytest.mark.parametrize('mm, speed', [(90, 5.0), (90, 14.9), (90, 30.0), (90, 50.0), (90, 170.0), (110, 15.0),
                                       (110, 30.0), (110, 50.0)])
@pytest.mark.parametrize('name', [codes.MITRE_BEND, codes.T_JOINT])
def test_a_turn_at_a_speed_outside_its_rows_range_is_refused_with_the_reason(name, mm, speed):
    reason = check(name, codes.LEFT, distance=800.0, speed=speed, robot=view(math.pi, SIDEWAYS[mm]), mm=mm)
    low, high = TURN_SPEEDS[mm]
    assert reason.startswith('a turn is taken at %d to %d mm/s (0: 25 mm/s), not %g mm/s' % (low, high, speed)), reason
    assert 'config/guards_%d.yaml turn goal_speed_min / goal_speed_max' % mm in reason
    assert 'the middle never swung round' in reason


def test_straight_on_through_a_t_joint_keeps_the_whole_drive_range():
    assert check(codes.T_JOINT, codes.STRAIGHT, distance=800.0, speed=50.0) is None


class _TurnRow(object):
    """A diameter's guards whose turn row has some values replaced (a bad guard file)."""

    def __init__(self, guards, **values):
        self._guards, self._values = guards, values

    def row(self, key):
        row = self._guards.row(key)
        return dict(row, **self._values) if key == 'turn' else row

    def __getattr__(self, name):
        return getattr(self._guards, name)


@pytest.mark.parametrize('values, needle', [
    (dict(goal_speed_min=30.0, goal_speed_max=10.0), 'goal_speed_min 30 <= steer_speed 25 <= goal_speed_max 10'),
    (dict(goal_speed_min=0.0), 'goal_speed_min 0 <= steer_speed 25'),
    (dict(goal_speed_max='fast'), 'must be numbers (mm/s)'),
    (dict(goal_speed_min=None), 'must be numbers (mm/s)'),
])
def test_a_turn_speed_range_that_cannot_hold_is_refused_naming_the_file(values, needle):
    goal = Goal(codes.MITRE_BEND, codes.LEFT, 800.0, 0.0, 90)
    reason = PABS[codes.MITRE_BEND][1].for_goal(goal).check(goal, view(math.pi, SIDEWAYS_LEFT),
                                                           _TurnRow(BOOK.for_diameter(90), **values))
    assert reason.startswith('config/guards_90.yaml turn: ') and needle in reason, reason


class _TurnPrims(object):
    """Primitives that record (name, wheel speed mm/s, robot-s bound) and end each
    guard at once: the speed each turn phase asks for, no physics."""

    def __init__(self, guards):
        self.guards, self.wheels, self.ran = guards, 0.0, []
        turn = guards.row('turn')
        self.view = RobotView(dict(SIDEWAYS_LEFT, bend_ii=float(turn['steered_rad']), bend_iii=0.0), math.pi,
                              0.0, 0.0, 1.0, {})

    def latest(self):
        return self.view

    def change_control_mode(self, joint, mode):
        """Modes do not matter here."""

    def move_module(self, joint, counts):
        """Setpoints do not matter here."""

    def drive_at_velocity(self, mm_s):
        self.wheels = mm_s

    def follow(self, name, act, done, text, timeout):
        self.ran.append((name, self.wheels, timeout))
        return self.view

    def wait_for(self, name, guard, text, timeout=None):
        self.ran.append((name, self.wheels, timeout))
        return self.view


def turn_phases(speed, mm=90):
    """(primitive, wheel mm/s, robot-s bound) of steering, swinging and pulling at the goal's ``speed``."""
    guards = BOOK.for_diameter(mm)
    prims = _TurnPrims(guards)
    goal = Goal(codes.MITRE_BEND, codes.LEFT, 800.0, speed, mm)
    ctx = PabContext(prims, prims, guards, goal, lambda *state: None)
    pab = PABS[codes.MITRE_BEND][1].for_goal(goal)
    pab.actions()[jn.STEERING_FRONT](ctx)
    pab.actions()[jn.SWINGING_MIDDLE](ctx)
    pab.actions()[jn.BRINGING_REAR](ctx)
    return prims.ran


@pytest.mark.parametrize('mm', [90, 110])
def test_a_turn_steers_and_swings_at_the_goals_speed_and_pulls_at_the_rows(mm):
    turn = BOOK.for_diameter(mm).row('turn')
    steer_s = float(turn['steer_base_s']) + float(turn['steer_s_per_mm']) * 800.0
    swing_s = pull_s = float(turn['timeout_s'])
    assert turn_phases(0.0, mm) == [('steer front', 25.0, steer_s), ('swing the middle', 25.0, swing_s),
                                    ('bring the rear through', 80.0, pull_s)]
    assert turn_phases(30.0, mm) == [('steer front', 30.0, steer_s), ('swing the middle', 30.0, swing_s),
                                     ('bring the rear through', 80.0, pull_s)]       # faster: not shortened


def test_a_slower_turn_stretches_the_time_bounds_of_what_it_slows_by_the_ratio_of_the_speeds():
    assert turn_phases(15.0) == [('steer front', 15.0, pytest.approx(25.0 / 15.0 * (45.0 + 0.15 * 800.0))),
                                 ('swing the middle', 15.0, pytest.approx(25.0 / 15.0 * 60.0)),
                                 ('bring the rear through', 80.0, 60.0)]

# --- a turn re-sent after a cancel ----------------------------------------------
#: What the robot sensed 2 s after a MITRE_BEND LEFT was cancelled in the
#: twin (bend_left_90, python3 bench/junction_turn_resume --cancel-at ...):
#: cancelled in -> (angles rad, springs mNm, roll rad, the step that continues it).
CANCELLED = {
    'unclamping front partial': (dict(bend_i=-0.64, bend_ii=-0.05, bend_iii=0.59, bend_iv=-0.71),
                                 dict(bend_i=-76, bend_ii=-6, bend_iii=60, bend_iv=234), 3.11, jn.STEERING_FRONT),
    'steering, in the straight pipe': (dict(bend_i=-0.90, bend_ii=0.45, bend_iii=0.40, bend_iv=-0.79),
                                       dict(bend_i=-56, bend_ii=-115, bend_iii=3, bend_iv=236), 3.12,
                                       jn.STEERING_FRONT),
    'steering, the front poking round': (dict(bend_i=0.79, bend_ii=0.42, bend_iii=0.41, bend_iv=-0.83),
                                         dict(bend_i=0, bend_ii=-95, bend_iii=1, bend_iv=239), 3.12,
                                         jn.STEERING_FRONT),
    'clamping front at the corner': (dict(bend_i=0.02, bend_ii=1.56, bend_iii=0.40, bend_iv=-0.80),
                                     dict(bend_i=-85, bend_ii=-187, bend_iii=-1, bend_iv=260), 3.16,
                                     jn.CLAMPING_AT_CORNER),
    'swinging, just started': (dict(bend_i=-0.47, bend_ii=1.75, bend_iii=0.48, bend_iv=-0.80),
                               dict(bend_i=155, bend_ii=-169, bend_iii=41, bend_iv=255), 3.16, jn.CLAMPING_AT_CORNER),
    # re-sent at once (--hold 0, MuJoCo 3.2.3): Bend II opened below the corner clamp's 1.55, Bend III under 0.85
    'swinging, Bend II opening first': (dict(bend_i=-0.57, bend_ii=1.47, bend_iii=0.83, bend_iv=-0.83),
                                        dict(bend_i=231, bend_ii=-82, bend_iii=87, bend_iv=260), 3.13,
                                        jn.SWINGING_MIDDLE),
    'swinging, reads Idle Clamped': (dict(bend_i=-0.65, bend_ii=1.10, bend_iii=1.21, bend_iv=-0.79),
                                     dict(bend_i=204, bend_ii=-118, bend_iii=187, bend_iv=258), 3.13,
                                     jn.SWINGING_MIDDLE),
    'swung': (dict(bend_i=-0.68, bend_ii=0.64, bend_iii=1.66, bend_iv=-0.76),
              dict(bend_i=225, bend_ii=-111, bend_iii=146, bend_iv=288), 3.12, jn.BRINGING_REAR),
    'bringing the rear, Bend III in the corner': (dict(bend_i=-0.69, bend_ii=0.39, bend_iii=1.60, bend_iv=-0.40),
                                                  dict(bend_i=247, bend_ii=-3, bend_iii=-1, bend_iv=182), 3.13,
                                                  jn.BRINGING_REAR),
    'bringing the rear, Bend IV round': (dict(bend_i=-0.69, bend_ii=0.38, bend_iii=0.16, bend_iv=0.61),
                                         dict(bend_i=258, bend_ii=-8, bend_iii=-216, bend_iv=-89), 3.16,
                                         jn.BRINGING_REAR),
    'clamping rear, Bend IV still round': (dict(bend_i=-0.68, bend_ii=0.43, bend_iii=-0.10, bend_iv=0.23),
                                           dict(bend_i=241, bend_ii=-38, bend_iii=-34, bend_iv=-35), 3.11,
                                           jn.BRINGING_REAR),
}
#: Sensed like a robot clamping its rear in a straight pipe: refused (Clamp Sideways first).
REAR_CLAMPING_PAST_THE_CORNER = (dict(bend_i=-0.68, bend_ii=0.38, bend_iii=0.35, bend_iv=-0.56),
                                 dict(bend_i=256, bend_ii=-5, bend_iii=-198, bend_iv=-66), 3.12)


def cancelled(angles, springs, roll):
    return view(roll, dict(CLAMPED, front_tilt=0.17, **angles), springs)


def first_step(name, option, robot, mm=90):
    goal = Goal(name, option, 800.0, 0.0, mm)
    guards = BOOK.for_diameter(mm)
    return jn.first_step(PABS[name][1].for_goal(goal).sensed_facts(guards, robot))


@pytest.mark.parametrize('where', sorted(CANCELLED))
def test_a_turn_re_sent_after_a_cancel_resumes_at_the_step_that_continues_it(where):
    angles, springs, roll, step = CANCELLED[where]
    robot = cancelled(angles, springs, roll)
    assert check(codes.MITRE_BEND, codes.LEFT, distance=800.0, robot=robot) is None
    assert first_step(codes.MITRE_BEND, codes.LEFT, robot) == step
    assert first_step(codes.T_JOINT, codes.LEFT, robot) == step        # the same steps: the kind is not sensed


@pytest.mark.parametrize('where', sorted(CANCELLED))
def test_a_turn_cancelled_toward_one_side_is_not_resumed_toward_the_other(where):
    angles, springs, roll, _ = CANCELLED[where]
    reason = check(codes.MITRE_BEND, codes.RIGHT, distance=800.0, robot=cancelled(angles, springs, roll))
    assert reason is not None and ('toward the LEFT' in reason or 'Clamp Sideways RIGHT first' in reason), reason


@pytest.mark.parametrize('where', sorted(w for w in CANCELLED if CANCELLED[w][3] != jn.STEERING_FRONT))
def test_half_round_a_corner_a_turn_is_refused_toward_the_other_side_and_straight_on(where):
    angles, springs, roll, _ = CANCELLED[where]
    robot = cancelled(angles, springs, roll)
    assert 'half round a corner toward the LEFT' in check(codes.MITRE_BEND, codes.RIGHT, 800.0, robot=robot)
    reason = check(codes.T_JOINT, codes.STRAIGHT, 800.0, robot=robot)
    assert 'starts clamped straight' in reason and 'half round a corner toward the LEFT' in reason


def test_the_rear_clamping_as_in_a_straight_pipe_asks_for_clamp_sideways_first():
    reason = check(codes.MITRE_BEND, codes.LEFT, 800.0, robot=cancelled(*REAR_CLAMPING_PAST_THE_CORNER))
    assert 'Clamp Sideways LEFT first' in reason and 'cannot sense which' in reason


def test_round_a_corner_with_neither_part_clamped_is_refused_with_where_it_is():
    angles, springs, roll, _ = CANCELLED['swinging, reads Idle Clamped']
    loose = dict(springs, bend_i=0, bend_iv=0)
    reason = check(codes.MITRE_BEND, codes.LEFT, 800.0, robot=cancelled(angles, loose, roll))
    assert 'cannot finish the turn from here' in reason and 'Bend III 1.21 rad' in reason


def test_a_robot_in_a_corner_never_starts_a_turn_from_its_beginning():
    for facts in ALL_FACTS:
        if in_a_corner(facts):
            assert jn.first_step(facts) != jn.LIFTING_FRONT, facts


def test_a_turn_never_resumes_with_the_roll_away_from_its_side():
    for facts in ALL_FACTS:
        if facts.turn and not facts.toward and not facts.straight:
            assert jn.first_step(facts) is None, facts


def test_a_resumed_step_needs_its_clamped_part():
    """Swinging pushes off the clamped rear, bringing pulls with the clamped front."""
    for facts in ALL_FACTS:
        step = jn.first_step(facts)
        if step in (jn.STEERING_FRONT, jn.CLAMPING_AT_CORNER, jn.SWINGING_MIDDLE):
            assert facts.trail, facts
        if step == jn.BRINGING_REAR:
            assert facts.lead, facts


# --- a turn re-sent after a cancel while driving into the new pipe ----------------
#: A turn cancelled in its last steps, clamped sideways in the new pipe: what
#: the robot senses is a robot clamped before a bend (twin, 2 s after a cancel
#: in "driving into the new pipe", bend_left_90).
AFTER_THE_CORNER = (dict(bend_i=-0.69, bend_ii=0.39, bend_iii=0.39, bend_iv=-0.78),
                    dict(bend_i=239, bend_ii=1, bend_iii=3, bend_iv=236), 3.13)


def test_a_turn_remembered_past_the_corner_goes_on_from_where_its_record_says():
    """The record (rear_through / driving_in / driven_in) never starts a turn nor resumes a corner step."""
    corner_steps = {jn.LIFTING_FRONT, jn.STEERING_FRONT, jn.CLAMPING_AT_CORNER, jn.SWINGING_MIDDLE,
                    jn.BRINGING_REAR}
    for facts in ALL_FACTS:
        step = jn.first_step(facts)
        if facts.turn and past_the_corner(facts):
            assert step not in corner_steps, facts
        if facts.turn and facts.toward and facts.driven_in:
            assert step == jn.STRAIGHTENING, facts
        if facts.turn and facts.toward and facts.driving_in and not facts.driven_in and facts.lead and facts.trail:
            assert step == jn.DRIVING_IN, facts
        if (facts.turn and facts.toward and facts.trail_through and not (facts.driving_in or facts.driven_in)
                and facts.lead):
            assert step == jn.CLAMPING_REAR, facts
        if step == jn.DRIVING_IN:
            assert facts.lead and facts.trail, facts       # drives clamped only
        if step == jn.CLAMPING_REAR:
            assert facts.lead, facts                      # the front holds while the rear clamps


def _past_the_corner(record, odometry_mm, mm=90):
    """The first step of MITRE_BEND LEFT re-sent with the server's ``record``,
    the robot as after the corner with its odometry at ``odometry_mm``."""
    angles, springs, roll = AFTER_THE_CORNER
    robot = cancelled(angles, springs, roll)._replace(odometry=odometry_mm)
    goal = Goal(codes.MITRE_BEND, codes.LEFT, 800.0, 0.0, mm)
    pab = PABS[codes.MITRE_BEND][1].for_goal(goal)
    pab.carry_on(record)
    return pab.check(goal, robot, BOOK.for_diameter(mm)), jn.first_step(pab.sensed_facts(BOOK.for_diameter(mm), robot))


def test_cancelled_while_driving_in_the_same_turn_re_sent_drives_what_is_left():
    record = jn.PastCorner('driving_in', 1000.0, 1150.0)
    assert _past_the_corner(record, 1060.0) == (None, jn.DRIVING_IN)
    assert _past_the_corner(record._replace(fact='driven_in', to_mm=1158.0), 1158.0) == (None, jn.STRAIGHTENING)


def test_cancelled_while_clamping_the_rear_that_came_through_the_same_turn_re_sent_clamps_it():
    """Front clamped, rear partly clamped, no bend round a corner: sensed, it reads
    like a robot part-clamped in a straight pipe (Clamp Sideways first, which
    ended the turn 150 mm short); the record says the rear came through."""
    angles, springs, roll = REAR_CLAMPING_PAST_THE_CORNER
    robot = cancelled(angles, springs, roll)._replace(odometry=1003.0)
    goal = Goal(codes.MITRE_BEND, codes.LEFT, 800.0, 0.0, 90)
    pab = PABS[codes.MITRE_BEND][1].for_goal(goal)
    pab.carry_on(jn.PastCorner('trail_through', 1000.0, 1000.0))
    guards = BOOK.for_diameter(90)
    assert pab.check(goal, robot, guards) is None
    assert jn.first_step(pab.sensed_facts(guards, robot)) == jn.CLAMPING_REAR


@pytest.mark.parametrize('odometry_mm', [985.0, 1165.5, 40.0])
def test_a_robot_moved_since_the_drive_in_is_not_resumed_there(odometry_mm):
    """Outside the drive in (give or take the drive's 10 mm tolerance) the record
    says nothing: clamped sideways, the re-sent goal is a new turn."""
    assert _past_the_corner(jn.PastCorner('driving_in', 1000.0, 1150.0), odometry_mm) == (None, jn.LIFTING_FRONT)


def test_without_the_record_the_same_robot_starts_a_new_turn():
    assert _past_the_corner(None, 1060.0) == (None, jn.LIFTING_FRONT)
