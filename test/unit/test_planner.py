"""Route planner (pirate.supervisory.planner): from named points to PAB goals.

Expected distances are derived here from the map and the settings, never
read back from the planner."""
import copy
import os

import pytest
import yaml

from pirate import paths
from pirate.sequencer import goals
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.junctions import required_clamp
from pirate.supervisory import planner
from pirate.world import network
from fakes import BookWithoutJunctionKey

with open(os.path.join(paths.CONFIG_DIR, 'supervisory.yaml')) as _f:
    SETTINGS = yaml.safe_load(_f)
MAX_DRIVE_MM = 5000.0
FRONT = SETTINGS['robot']['front_mm']
REAR = SETTINGS['robot']['rear_mm']
APPROACH = SETTINGS['approach_mm']
CLEAR = SETTINGS['clear_mm']
TURN_END = SETTINGS['turn_end_mm'][90]
TURN_END_FROM_RUN = SETTINGS['turn_end_from_run_mm'][90]
TURN_END_REAR_FIRST = SETTINGS['turn_end_rear_first_mm'][90]
SEARCH = SETTINGS['search_mm']


def world(pieces, points, diameter=90):
    return network.build({'name': 'test', 'diameter_mm': diameter, 'pieces': pieces,
                          'points': [{'name': n, 'at_mm': at} for n, at in points.items()]})


def run(net, *route, **kw):
    return planner.plan(net, list(route), kw.pop('settings', SETTINGS), MAX_DRIVE_MM, **kw)


def pabs(route_plan):
    return [(s.pab, s.option) for s in route_plan.steps]


BEND_LEFT = [{'type': 'straight', 'length_mm': 2000}, {'type': 'mitre', 'turn': 'left'},
             {'type': 'straight', 'length_mm': 2000}, {'type': 'cap'}]


def test_straight_route_is_clamp_drive_home():
    net = world([{'type': 'straight', 'length_mm': 3000}], {'pit': 400, 'target': 1900})
    steps = run(net, 'pit', 'target').steps
    assert [(s.pab, s.option) for s in steps] == [('CLAMP_STRAIGHT', None), ('DRIVE', None), ('HOME', None)]
    assert steps[1].distance_mm == pytest.approx(1500.0)
    assert steps[1].speed_mm_s == SETTINGS['speed_mm_s'] and steps[1].pipe_diameter == 90


def test_mitre_left_clamps_sideways_left_and_stops_the_front_before_it():
    net = world(BEND_LEFT, {'pit': 300, 'target': 3000})
    steps = run(net, 'pit', 'target', speed_mm_s=60).steps
    assert pabs(run(net, 'pit', 'target')) == [
        ('CLAMP_SIDEWAYS', 'LEFT'), ('DRIVE', None), ('MITRE_BEND', 'LEFT'), ('DRIVE', None), ('HOME', None)]
    entry_mm, exit_mm = 2000, 2090
    assert steps[1].distance_mm == pytest.approx(entry_mm - FRONT - APPROACH - 300)
    assert steps[2].distance_mm == SEARCH and steps[2].junction.name == 'mitre_1'
    assert steps[2].end_m * 1000 == pytest.approx(exit_mm + TURN_END)
    assert steps[3].distance_mm == pytest.approx(3000 - exit_mm - TURN_END)
    # The mission's speed is the drives'; the clamp and the junction PAB run at their own (0).
    assert [s.speed_mm_s for s in steps] == [0.0, 60, 0.0, 60, 0.0]


def test_a_turn_in_110_mm_ends_where_the_110_mm_turn_leaves_the_robot():
    """The turn's end is the robot's geometry in that pipe: one figure per diameter."""
    ends = SETTINGS['turn_end_mm']
    assert ends[110] > ends[90] + 100       # the twin: 572-576 against 394-404 mm
    steps = run(world(BEND_LEFT, {'pit': 300, 'target': 3000}, diameter=110), 'pit', 'target').steps
    exit_mm = 2000 + 110
    assert steps[2].pab == 'MITRE_BEND' and steps[2].pipe_diameter == 110
    assert steps[2].end_m * 1000 == pytest.approx(exit_mm + ends[110])
    assert steps[3].distance_mm == pytest.approx(3000 - exit_mm - ends[110])


def test_a_t_joint_from_its_run_ends_where_its_own_figure_says_and_a_mitre_where_the_diameters_does():
    """turn_end_from_run_mm (90 mm: the middle swings round the open run
    ahead and ends ~45 mm further, twin); 110 mm has none, turn_end_mm serves."""
    assert TURN_END_FROM_RUN > TURN_END + 30
    for diameter, end in ((90, TURN_END_FROM_RUN), (110, SETTINGS['turn_end_mm'][110])):
        net = world([{'type': 'straight', 'length_mm': 1500},
                     {'type': 'tee', 'enter': 'run', 'side': 'left', 'leave': 'branch'},
                     {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 2500}, diameter=diameter)
        tee_step = run(net, 'a', 'b').steps[2]
        assert tee_step.junction.from_run and tee_step.end_m * 1000 == pytest.approx(1500 + diameter + end)
    branch = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'tee', 'enter': 'branch', 'side': 'left'},
                    {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 2500})
    tee_step = run(branch, 'a', 'b').steps[2]
    assert not tee_step.junction.from_run and tee_step.end_m * 1000 == pytest.approx(1500 + 90 + TURN_END)


def test_a_turn_in_a_pipe_without_a_measured_turn_end_is_refused():
    settings = dict(SETTINGS, turn_end_mm={90: 386})
    with pytest.raises(planner.PlanError, match='no turn end measured for a 110 mm pipe'):
        run(world(BEND_LEFT, {'pit': 300, 'target': 3000}, diameter=110), 'pit', 'target', settings=settings)


def test_the_way_back_takes_the_bend_rear_first_still_clamped_sideways():
    """The turn ended lying on the side it needs (no re-clamp on the way back)."""
    net = world(BEND_LEFT, {'pit': 300, 'target': 3000})
    route_plan = run(net, 'pit', 'target', 'pit')
    back = route_plan.steps[4:]
    assert [(s.pab, s.option) for s in back] == [
        ('DRIVE', None), ('MITRE_BEND', 'LEFT'), ('DRIVE', None), ('HOME', None)]
    entry_mm, exit_mm = 2000, 2090
    assert back[0].distance_mm == pytest.approx((exit_mm + REAR + APPROACH) - 3000)
    assert back[1].distance_mm == -SEARCH
    assert back[1].end_m * 1000 == pytest.approx(entry_mm - TURN_END_REAR_FIRST)   # before the entry
    assert back[2].distance_mm == pytest.approx(300 - (entry_mm - TURN_END_REAR_FIRST))
    assert back[2].end_m == pytest.approx(0.3)


@pytest.mark.parametrize('route, leaves_mm', [
    (('pit', 'near'), 2090 + TURN_END),                       # front first: past the bend's exit
    (('pit', 'target', 'near_back'), 2000 - TURN_END_REAR_FIRST)])   # rear first: before its entry
def test_a_point_the_turn_carries_the_robot_past_is_refused_naming_where_the_turn_leaves_it(route, leaves_mm):
    points = {'pit': 300, 'target': 3000, 'near': 2090 + TURN_END - 100, 'near_back': 2000 - TURN_END_REAR_FIRST + 100}
    with pytest.raises(planner.PlanError) as refused:
        run(world(BEND_LEFT, points), *route)
    assert '%s (%d mm) lies before where mitre_1 leaves the robot (its middle at %d mm)' % (
        route[-1], points[route[-1]], leaves_mm) in str(refused.value)


def tee_run(side):
    return world([{'type': 'straight', 'length_mm': 1500}, {'type': 'tee', 'enter': 'run', 'side': side},
                  {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 2500})


def test_straight_through_a_tee_open_upward_clamps_with_the_front_v_facing_it():
    """The PAB senses the T-joint only with the V's apex toward the hole:
    upright below a hole above."""
    assert pabs(run(tee_run('up'), 'a', 'b'))[:3] == [('CLAMP_STRAIGHT', None), ('DRIVE', None),
                                                       ('T_JOINT', 'STRAIGHT')]


@pytest.mark.parametrize('side', ['left', 'right'])
def test_straight_past_a_tee_open_to_a_side_drives_clamped_straight(side):
    """Upright, no wheel meets a side hole: one Drive past it, until the rear
    end is approach_mm past its far edge, then on to the target; no junction
    PAB, so nothing is anchored there (junctions.driven_past)."""
    route_plan = run(tee_run(side), 'a', 'b')
    assert pabs(route_plan) == [('CLAMP_STRAIGHT', None), ('DRIVE', None), ('DRIVE', None), ('HOME', None)]
    past, on = route_plan.steps[1:3]
    exit_mm = 1500 + 90
    assert past.distance_mm == pytest.approx(exit_mm + REAR + APPROACH - 200)
    assert 'past tee_1 (open %s' % side in past.note and past.junction is None
    assert on.distance_mm == pytest.approx(2500 - exit_mm - REAR - APPROACH)
    planner.check_runnable(route_plan)


@pytest.mark.parametrize('side', ['left', 'right'])
def test_driving_past_a_side_tee_stops_at_the_target_if_it_comes_first(side):
    net = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'tee', 'enter': 'run', 'side': side},
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 1700})
    route_plan = run(net, 'a', 'b')
    assert pabs(route_plan) == [('CLAMP_STRAIGHT', None), ('DRIVE', None), ('HOME', None)]
    assert route_plan.steps[1].distance_mm == pytest.approx(1500.0)


def test_driving_back_past_a_side_tee_clears_it_with_the_front_end():
    """Either way: on the way back the front end trails (no junction PAB, so
    nothing is taken rear first)."""
    route_plan = run(tee_run('right'), 'b', 'a')
    assert pabs(route_plan) == [('CLAMP_STRAIGHT', None), ('DRIVE', None), ('DRIVE', None), ('HOME', None)]
    assert route_plan.steps[1].end_m * 1000 == pytest.approx(1500 - FRONT - APPROACH)
    planner.check_runnable(route_plan)


def test_straight_through_a_tee_open_downward_is_refused_no_clamp_faces_it():
    with pytest.raises(planner.PlanError, match=r'tee_1: a T-joint open down cannot be gone straight through'):
        run(tee_run('down'), 'a', 'b')


@pytest.mark.parametrize('diameter', [90, 110])
@pytest.mark.parametrize('taken', [True, False], ids=['guards with the row', 'guards without it'])
def test_a_junction_step_the_pab_does_not_start_from_the_held_clamp_is_refused(diameter, taken):
    """check_runnable reads the PAB's own declaration (pabs/junction.py) and,
    for straight on lying on a side, its guards' verdict (taken where the
    junction row has straight_sideways_speed_min: 90 and 110 mm): a T_JOINT
    STRAIGHT step held sideways runs where the guards take it and is refused
    before anything moves where they do not, naming the clamp the route holds
    there. (The planner itself drives past a T-joint open to a side.)"""
    net = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'tee', 'enter': 'run', 'side': 'up'},
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 2500}, diameter=diameter)
    route_plan = run(net, 'a', 'b')
    planner.check_runnable(route_plan)
    sideways = route_plan._replace(steps=[step._replace(holds=required_clamp('tee', 'straight', 'right'))
                                          if step.pab == 'T_JOINT' else step for step in route_plan.steps])
    if taken:
        planner.check_runnable(sideways)
        return
    book = BookWithoutJunctionKey(GuardBook(*load_files()), 'straight_sideways_speed_min')
    planner.check_runnable(route_plan, book=book)
    with pytest.raises(planner.PlanError, match=r"step 3 \(T_JOINT STRAIGHT, tee_1\): the route holds clamp "
                                                r"sideways RIGHT there \(the front V facing up\), but T_JOINT "
                                                r"STRAIGHT starts from clamp straight only"):
        planner.check_runnable(sideways, book=book)


def test_entering_a_tee_through_its_branch_turns_toward_its_side():
    net = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'tee', 'enter': 'branch', 'side': 'right'},
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 2500})
    assert pabs(run(net, 'a', 'b'))[:3] == [('CLAMP_SIDEWAYS', 'RIGHT'), ('DRIVE', None), ('T_JOINT', 'RIGHT')]


@pytest.mark.parametrize('side', ['left', 'right'])
def test_entering_a_tee_through_its_run_and_leaving_by_its_branch_is_a_turn_toward_its_side(side):
    """The route turns into the branch: Clamp Sideways toward the turn, T_JOINT
    LEFT / RIGHT, ending where a turn leaves the robot; the run ahead is the
    side not taken (straight), and the real server runs the plan."""
    net = world([{'type': 'straight', 'length_mm': 1500},
                 {'type': 'tee', 'enter': 'run', 'side': side, 'leave': 'branch'},
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 2500})
    route_plan = run(net, 'a', 'b')
    assert pabs(route_plan) == [('CLAMP_SIDEWAYS', side.upper()), ('DRIVE', None), ('T_JOINT', side.upper()),
                                ('DRIVE', None), ('HOME', None)]
    tee = route_plan.steps[2].junction
    assert (tee.kind, tee.direction, tee.open_side) == ('tee', side, 'straight')
    assert required_clamp(tee.kind, tee.direction, tee.open_side) == (route_plan.steps[0].pab, side.upper())
    exit_mm = 1500 + 90
    assert route_plan.steps[1].distance_mm == pytest.approx(1500 - FRONT - APPROACH - 200)
    assert route_plan.steps[2].end_m * 1000 == pytest.approx(exit_mm + TURN_END_FROM_RUN)
    assert route_plan.steps[3].distance_mm == pytest.approx(2500 - exit_mm - TURN_END_FROM_RUN)
    planner.check_runnable(route_plan)


def test_a_bend_up_needs_no_sideways_clamp():
    net = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'mitre', 'turn': 'up'},
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 2500})
    assert pabs(run(net, 'a', 'b'))[:3] == [('CLAMP_STRAIGHT', None), ('DRIVE', None), ('MITRE_BEND', 'UP')]


def test_a_drive_longer_than_one_goal_may_go_is_split_evenly():
    net = world([{'type': 'straight', 'length_mm': 12000}], {'a': 500, 'b': 11500})
    drives = [s.distance_mm for s in run(net, 'a', 'b').steps if s.pab == 'DRIVE']
    assert len(drives) == 3 and all(d <= MAX_DRIVE_MM for d in drives)
    assert sum(drives) == pytest.approx(11000.0)


@pytest.mark.parametrize('side, then', [('up', ['DRIVE', 'T_JOINT', 'DRIVE']), ('left', ['DRIVE', 'DRIVE'])])
def test_two_junctions_in_a_row_reclamp_between_them_only_when_needed(side, then):
    """After a bend up (clamped straight) a T-joint open upward, or one open
    to a side driven past, needs no other clamp."""
    net = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'mitre', 'turn': 'up'},
                 {'type': 'straight', 'length_mm': 1500}, {'type': 'tee', 'enter': 'run', 'side': side},
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 4000})
    assert [p for p, _ in pabs(run(net, 'a', 'b'))] == ['CLAMP_STRAIGHT', 'DRIVE', 'MITRE_BEND'] + then + ['HOME']


@pytest.mark.parametrize('second, then', [
    ({'type': 'mitre', 'turn': 'left'}, ['DRIVE', 'MITRE_BEND', 'DRIVE']),
    ({'type': 'tee', 'enter': 'run', 'side': 'up'}, ['CLAMP_STRAIGHT', 'DRIVE', 'T_JOINT', 'DRIVE']),
    ({'type': 'tee', 'enter': 'run', 'side': 'left'}, ['CLAMP_STRAIGHT', 'DRIVE', 'DRIVE'])])
def test_after_a_turn_the_robot_still_lies_on_its_side(second, then):
    """A turn ends clamped sideways (the junction PAB's straightening is Clamp
    Sideways): a second turn the same way needs no clamp, a T-joint open
    upward, or one open to a side driven past, the straight clamp first."""
    net = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'mitre', 'turn': 'left'},
                 {'type': 'straight', 'length_mm': 1500}, second,
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 4000})
    assert [p for p, _ in pabs(run(net, 'a', 'b'))] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND'] + then + ['HOME']


def test_junctions_are_named_in_path_order():
    net = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'mitre', 'turn': 'up'},
                 {'type': 'straight', 'length_mm': 1500}, {'type': 'tee', 'enter': 'run', 'side': 'left'},
                 {'type': 'straight', 'length_mm': 1500}, {'type': 'mitre', 'turn': 'right'},
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200})
    assert [(j.name, j.direction, j.open_side) for j in planner.junctions(net)] == [
        ('mitre_1', 'up', None), ('tee_1', 'straight', 'left'), ('mitre_2', 'right', None)]


def test_the_printed_plan_has_one_line_per_goal():
    net = world(BEND_LEFT, {'pit': 300, 'target': 3000})
    route_plan = run(net, 'pit', 'target')
    lines = planner.format_plan(route_plan)
    assert len(lines) == 1 + len(route_plan.steps)
    assert 'MITRE_BEND' in lines[3] and 'LEFT' in lines[3] and 'mitre_1' in lines[3]


@pytest.mark.parametrize('route, reason', [
    (['pit'], 'at least two points'),
    (['pit', 'nowhere'], "no point 'nowhere'"),
    (['pit', 'pit'], 'the same place'),
    (['pit', 'in_bend'], 'lies in a mitre'),
    (['near_bend', 'target'], 'too close to mitre_1'),
    (['pit', 'just_after'], 'lies before where mitre_1 leaves the robot'),
])
def test_routes_the_map_cannot_serve_are_refused_with_the_reason(route, reason):
    net = world(BEND_LEFT, {'pit': 300, 'target': 3000, 'in_bend': 2050, 'near_bend': 1800, 'just_after': 2200})
    with pytest.raises(planner.PlanError, match=reason):
        run(net, *route)


def test_a_junction_the_robot_cannot_take_in_that_diameter_is_refused():
    settings = copy.deepcopy(SETTINGS)
    settings['takeable'][110]['mitre'] = ['left', 'right']
    net = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'mitre', 'turn': 'down'},
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 2500}, diameter=110)
    with pytest.raises(planner.PlanError, match=r'mitre_1 \(mitre, down\) cannot be taken in a 110 mm pipe'):
        run(net, 'a', 'b', settings=settings)


@pytest.mark.parametrize('kind, direction, side, expected', [
    ('mitre', 'left', None, ('CLAMP_SIDEWAYS', 'LEFT')), ('mitre', 'right', None, ('CLAMP_SIDEWAYS', 'RIGHT')),
    ('mitre', 'up', None, ('CLAMP_STRAIGHT', None)), ('mitre', 'down', None, ('CLAMP_STRAIGHT', None)),
    ('tee', 'straight', 'left', ('CLAMP_SIDEWAYS', 'LEFT')), ('tee', 'straight', 'up', ('CLAMP_STRAIGHT', None)),
])
def test_required_clamp_puts_the_bending_plane_in_the_turn(kind, direction, side, expected):
    assert tuple(required_clamp(kind, direction, side)) == expected


def test_a_mitre_cannot_be_taken_straight():
    with pytest.raises(ValueError, match='mitre cannot be taken'):
        required_clamp('mitre', 'straight')


@pytest.mark.parametrize('points, reason', [
    ([{'name': 'a', 'at_mm': 10}, {'name': 'a', 'at_mm': 20}], 'named twice'),
    ([{'name': 'a', 'at_mm': 99999}], 'outside the network'),
    ([{'name': 'a'}], r'a point is \{name'),
    ({'a': 1}, 'a list of'),
])
def test_bad_points_in_a_map_are_refused(points, reason):
    with pytest.raises(network.WorldError, match=reason):
        network.build({'pieces': [{'type': 'straight', 'length_mm': 1000}], 'points': points})


def test_plan_mission_prints_the_shipped_inspection_route(capsys):
    from pirate.supervisory import plan_cli
    assert plan_cli.main(['inspection_90', 'launch_pit', 'target', 'launch_pit']) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith('plan on inspection_90: launch_pit -> target -> launch_pit')
    taken = [line.split()[1] for line in out[1:] if 'MITRE_BEND' in line or 'T_JOINT' in line]
    assert taken == ['MITRE_BEND', 'MITRE_BEND'] * 2          # its T-joint, open to the right, is driven past
    assert sum(line.split()[1] == 'DRIVE' and 'past tee_1 (open right' in line for line in out) == 2
    assert out[-1].split()[1] == 'HOME'


@pytest.mark.parametrize('world, target, warning', [
    # its last bend turns down: not taken yet
    ('inspection_90', 'target', 'step 7 (MITRE_BEND DOWN, mitre_2): the Pirate Server cannot run MITRE_BEND DOWN yet'),
    # its T-joint opens to the right: driven past clamped straight
    ('inspection_90', 'past_tee', None),
    ('inspection_network_90', 'target', None),
])
def test_plan_mission_says_when_the_server_cannot_run_the_plan_yet(world, target, warning, capsys):
    from pirate.supervisory import plan_cli
    assert plan_cli.main([world, 'launch_pit', target]) == 0
    out, err = capsys.readouterr()
    assert out.splitlines()[-1].split()[1] == 'HOME'
    assert ('cannot run yet' in err and warning in err) if warning else err == ''


@pytest.mark.parametrize('argv, reason', [
    (['inspection_90', 'launch_pit', 'nowhere'], "no point 'nowhere'"),
    (['no_such_map', 'a', 'b'], 'cannot read'),
])
def test_plan_mission_refuses_with_the_reason_and_exit_2(argv, reason, capsys):
    from pirate.supervisory import plan_cli
    assert plan_cli.main(argv) == 2
    assert reason in capsys.readouterr().err


def test_run_mission_route_check_prints_the_plan_without_ros(capsys):
    from pirate.supervisory import mission_node
    assert mission_node.main(['run_mission', '--route', 'inspection_90', 'launch_pit', 'target', '--check']) == 0
    out = capsys.readouterr().out
    assert out.startswith('plan on inspection_90: launch_pit -> target') and 'MITRE_BEND' in out


def test_run_mission_route_refuses_a_route_before_sending_anything(capsys):
    from pirate.supervisory import mission_node
    assert mission_node.main(['run_mission', '--route', 'inspection_90', 'launch_pit', 'nowhere']) == 2
    assert "no point 'nowhere'" in capsys.readouterr().err


def test_a_route_the_server_cannot_run_is_refused_before_anything_moves():
    """A server without the junction PAB refuses a route through a bend at its
    junction step, by name; a server with it passes the same route."""
    route_plan = run(world(BEND_LEFT, {'pit': 300, 'target': 3000}), 'pit', 'target')
    with pytest.raises(planner.PlanError, match=r"step 3 \(MITRE_BEND LEFT, mitre_1\): the Pirate Server cannot "
                                                r"run MITRE_BEND LEFT yet"):
        planner.check_runnable(route_plan, built=lambda pab, option=None: pab != 'MITRE_BEND')
    planner.check_runnable(route_plan, built=lambda pab, option=None: True)


def test_a_turn_the_junction_pab_does_not_take_is_refused_by_the_real_server_table():
    """The junction PAB takes a mitre left / right but not up / down:
    the planner asks the server's own table with the direction, so a route
    through a bend down stops here, not at the bend; one through a bend left passes."""
    bend_down = [dict(BEND_LEFT[1], turn='down') if p['type'] == 'mitre' else p for p in BEND_LEFT]
    route_plan = run(world(bend_down, {'pit': 300, 'target': 3000}), 'pit', 'target')
    assert goals.built('MITRE_BEND', 'LEFT') and not goals.built('MITRE_BEND', 'DOWN')
    with pytest.raises(planner.PlanError, match=r"cannot run MITRE_BEND DOWN yet"):
        planner.check_runnable(route_plan)
    planner.check_runnable(run(world(BEND_LEFT, {'pit': 300, 'target': 3000}), 'pit', 'target'))


def test_the_way_back_through_a_junction_runs_where_the_pab_takes_it_rear_first():
    """The plan takes the bend rear first on the way back (a negative search
    distance); the junction PAB takes every direction it takes front first
    rear first too, so the round trip is runnable; a server that did not would
    have the route refused before anything moves, naming the step."""
    round_trip = run(world(BEND_LEFT, {'pit': 300, 'target': 3000}), 'pit', 'target', 'pit')
    assert goals.built('MITRE_BEND', 'LEFT', rear_first=True) and goals.built('DRIVE', rear_first=True)
    planner.check_runnable(round_trip)
    with pytest.raises(planner.PlanError, match=r"step 6 \(MITRE_BEND LEFT, mitre_1\): the Pirate Server cannot take "
                                                r"MITRE_BEND LEFT rear first yet \(not built\); the robot cannot "
                                                r"take this route back through mitre_1"):
        planner.check_runnable(round_trip, built=lambda pab, option=None, rear_first=False: not rear_first)


TEE_BRANCH = [{'type': 'straight', 'length_mm': 1500}, {'type': 'tee', 'enter': 'branch', 'side': 'right'},
              {'type': 'straight', 'length_mm': 1500}]
TEE_RUN_BRANCH = [{'type': 'straight', 'length_mm': 1500},
                  {'type': 'tee', 'enter': 'run', 'side': 'left', 'leave': 'branch'},
                  {'type': 'straight', 'length_mm': 1500}]
TEE_RUN_UP = [{'type': 'straight', 'length_mm': 1500}, {'type': 'tee', 'enter': 'run', 'side': 'up'},
              {'type': 'straight', 'length_mm': 1500}]


def there_and_back(pieces, diameter):
    length = sum(p.get('length_mm', 0) for p in pieces) + diameter
    return run(world(pieces, {'pit': 300, 'target': length - 500}, diameter=diameter), 'pit', 'target', 'pit')


@pytest.mark.parametrize('pieces', [BEND_LEFT, TEE_BRANCH, TEE_RUN_BRANCH, TEE_RUN_UP])
@pytest.mark.parametrize('diameter', [90, 110])
def test_every_route_back_through_a_junction_taken_in_is_planned(pieces, diameter):
    """There and back through each junction the PAB takes: the junction step
    on the way back searches backwards (negative distance) in the direction
    it was taken in, and the route ends where it began."""
    round_trip = there_and_back(pieces, diameter)
    there, back = [s for s in round_trip.steps if s.junction is not None]
    assert there.distance_mm > 0 > back.distance_mm and (there.pab, there.option) == (back.pab, back.option)
    assert back.note.endswith('rear first')
    assert round_trip.steps[-1].end_m == pytest.approx(0.3)


@pytest.mark.parametrize('diameter', [90, 110])
def test_the_way_back_through_a_bend_and_straight_on_through_a_tee_runs(diameter):
    for pieces in (BEND_LEFT, TEE_RUN_UP):
        planner.check_runnable(there_and_back(pieces, diameter))


@pytest.mark.parametrize('pieces', [TEE_BRANCH, TEE_RUN_BRANCH])
def test_the_way_back_round_a_t_joint_is_refused_with_why_the_rear_cannot_steer_into_it(pieces):
    """The rear module has no tilt: backing through a T-joint nothing turns
    it into the opening (twin), so that route back is refused before anything moves."""
    with pytest.raises(planner.PlanError, match=r"cannot take T_JOINT (LEFT|RIGHT) rear first yet \(the rear module "
                                                r"has no tilt.*back through tee_1"):
        planner.check_runnable(there_and_back(pieces, 90))
    planner.check_runnable(run(world(pieces, {'a': 300, 'b': 2600}), 'a', 'b'))


def test_a_junction_direction_the_goal_cannot_carry_is_refused(monkeypatch):
    monkeypatch.setitem(goals.PAB_OPTIONS, 'MITRE_BEND', ('LEFT', 'RIGHT'))   # a goal interface without DOWN
    net = world([{'type': 'straight', 'length_mm': 1500}, {'type': 'mitre', 'turn': 'down'},
                 {'type': 'straight', 'length_mm': 1500}], {'a': 200, 'b': 2500})
    with pytest.raises(planner.PlanError, match="MITRE_BEND takes LEFT / RIGHT, not DOWN"):
        planner.check_runnable(run(net, 'a', 'b'), built=lambda pab, option=None: True)


def test_run_mission_route_refuses_a_route_the_server_cannot_run_before_sending_anything(monkeypatch, capsys):
    from pirate.supervisory import mission_node
    monkeypatch.setattr(goals, 'built', lambda pab, option=None: pab != 'MITRE_BEND')
    assert mission_node.main(['run_mission', '--route', 'inspection_90', 'launch_pit', 'target']) == 2
    assert 'cannot run MITRE_BEND LEFT yet' in capsys.readouterr().err
