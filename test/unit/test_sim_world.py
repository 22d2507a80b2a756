"""World files: the shipped worlds load and lay out as drawn; every bad
file is refused with the file, the entry and the reason."""
import math
import os

import pytest
import yaml

from pirate import paths
from pirate.world import network

WORLDS = os.path.join(paths.CONFIG_DIR, 'worlds')


def _close(a, b):
    return all(abs(x - y) < 1e-9 for x, y in zip(a, b))


@pytest.mark.parametrize('name', ['straight_90', 'straight_110', 'network_90'])
def test_shipped_worlds_load(name):
    world = network.load(os.path.join(WORLDS, name + '.yaml'))
    assert world.pieces and world.length > 1.0
    assert world.pieces[world.locate(world.start_m)[0]].kind == 'straight'


def test_network_lays_out_left_then_tee_then_down():
    world = network.load(os.path.join(WORLDS, 'network_90.yaml'))
    kinds = [p.kind for p in world.pieces]
    assert kinds == ['straight', 'mitre', 'straight', 'tee', 'straight', 'mitre', 'straight', 'cap']
    d = 0.09
    # 900 mm along x, the mitre turns left: the next straight runs along +y.
    assert _close(world.pieces[1].exit.origin, (0.9 + d / 2, d / 2, 0.0))
    assert _close(world.pieces[2].entry.axes[0], (0.0, 1.0, 0.0))
    # The tee goes straight on; its open branch points right of travel (+x here).
    assert _close(world.pieces[3].stub.axes[0], (1.0, 0.0, 0.0))
    # The last mitre turns down: the last straight runs along -z.
    assert _close(world.pieces[6].entry.axes[0], (0.0, 0.0, -1.0))
    assert math.isclose(world.length, 0.9 + d + 0.5 + d + 0.5 + d + 0.4)


def test_tee_entered_through_its_branch_leaves_the_far_run_open():
    world = network.build({'pieces': [{'type': 'straight', 'length_mm': 500},
                                      {'type': 'tee', 'enter': 'branch', 'side': 'left'},
                                      {'type': 'straight', 'length_mm': 300}]})
    tee = world.pieces[1]
    assert _close(tee.exit.axes[0], (0.0, 1.0, 0.0))
    assert _close(tee.stub.axes[0], (0.0, -1.0, 0.0))


@pytest.mark.parametrize('side, turned_to, sign', [('left', (0.0, 1.0, 0.0), 1.0), ('right', (0.0, -1.0, 0.0), -1.0)])
def test_tee_entered_through_its_run_and_left_by_its_branch_turns_there_its_run_open_ahead(side, turned_to, sign):
    world = network.build({'pieces': [{'type': 'straight', 'length_mm': 500},
                                      {'type': 'tee', 'enter': 'run', 'side': side, 'leave': 'branch'},
                                      {'type': 'straight', 'length_mm': 300}]})
    tee, d = world.pieces[1], 0.09
    assert _close(tee.exit.axes[0], turned_to)                            # on along the branch
    assert _close(tee.exit.origin, (0.5 + d / 2, sign * d / 2, 0.0))     # the branch's mouth at the run's wall
    assert _close(tee.stub.axes[0], (1.0, 0.0, 0.0))                      # the run's far end, ahead, is the stub
    assert _close(tee.stub.origin, (0.5 + d / 2, 0.0, 0.0))
    assert _close(world.pieces[2].entry.axes[0], turned_to) and math.isclose(world.length, 0.5 + d + 0.3)
    assert network.turns_at_corner(tee)


def test_leave_run_is_the_default_straight_on():
    spec = {'type': 'tee', 'enter': 'run', 'side': 'up'}
    pieces = [{'type': 'straight', 'length_mm': 500}, spec, {'type': 'straight', 'length_mm': 300}]
    default, explicit = network.build({'pieces': pieces}), network.build({'pieces': [
        pieces[0], dict(spec, leave='run'), pieces[2]]})
    assert default.pieces[1].exit == explicit.pieces[1].exit and _close(default.pieces[1].exit.axes[0], (1, 0, 0))
    assert default.pieces[1].stub == explicit.pieces[1].stub and not network.turns_at_corner(default.pieces[1])


@pytest.mark.parametrize('mm', [90, 110])
@pytest.mark.parametrize('side', ['left', 'right'])
def test_the_run_branch_worlds_have_the_branch_entry_worlds_distances(side, mm):
    run_entry = network.load(os.path.join(WORLDS, 'tee_run_branch_%s_%d.yaml' % (side, mm)))
    branch_entry = network.load(os.path.join(WORLDS, 'tee_branch_%s_%d.yaml' % (side, mm)))
    assert run_entry.pieces[1].spec == {'type': 'tee', 'enter': 'run', 'side': side, 'leave': 'branch'}
    assert [p.length for p in run_entry.pieces] == [p.length for p in branch_entry.pieces]
    assert run_entry.start_m == branch_entry.start_m and run_entry.pieces[1].exit == branch_entry.pieces[1].exit


def _refusal(data, tmp_path):
    path = tmp_path / 'bad.yaml'
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(network.WorldError) as refused:
        network.load(str(path))
    return str(refused.value)


STRAIGHT = {'type': 'straight', 'length_mm': 500}


@pytest.mark.parametrize('data, entry, reason', [
    ({'pieces': [STRAIGHT, {'type': 'elbow'}]}, 'pieces[1]', 'unknown element'),
    ({'diameter_mm': 100, 'pieces': [STRAIGHT]}, 'diameter_mm', 'not supported'),
    ({'pieces': [dict(STRAIGHT, diameter_mm=75)]}, 'pieces[0]', 'not supported'),
    ({'pieces': [STRAIGHT, {'type': 'mitre', 'turn': 'left'}]}, 'pieces[1]', 'straight segment after it'),
    ({'pieces': [STRAIGHT, {'type': 'mitre', 'turn': 'left'}, {'type': 'tee', 'enter': 'run', 'side': 'up'},
                 STRAIGHT]}, 'pieces[1]', 'straight segment after it'),
    ({'pieces': [STRAIGHT, {'type': 'mitre', 'turn': 'sideways'}, STRAIGHT]}, 'pieces[1]', 'direction'),
    ({'pieces': [STRAIGHT, {'type': 'cap'}, STRAIGHT]}, 'pieces[1]', 'last piece'),
    ({'pieces': [STRAIGHT, {'type': 'straight'}]}, 'pieces[1]', 'missing'),
    ({'pieces': [STRAIGHT, {'type': 'straight', 'length_mm': 300, 'colour': 'red'}]}, 'pieces[1]', 'unknown'),
    ({'pieces': [{'type': 'straight', 'length_mm': 300}, {'type': 'mitre', 'turn': 'left'},
                 {'type': 'straight', 'length_mm': 100}, {'type': 'mitre', 'turn': 'left'},
                 {'type': 'straight', 'length_mm': 100}, {'type': 'mitre', 'turn': 'left'},
                 {'type': 'straight', 'length_mm': 400}]}, 'pieces[6]', 'overlaps pieces[0]'),
    ({'pieces': [STRAIGHT, {'type': 'tee', 'enter': 'branch', 'side': 'left', 'leave': 'branch'}, STRAIGHT]},
     'pieces[1]', 'can only be left by its run'),
    ({'pieces': [STRAIGHT, {'type': 'tee', 'enter': 'run', 'side': 'left', 'leave': 'side'}, STRAIGHT]},
     'pieces[1]', "leave 'side' is not one of"),
    ({'pieces': [STRAIGHT, {'type': 'tee', 'enter': 'top', 'side': 'left'}, STRAIGHT]},
     'pieces[1]', "enter 'top' is not one of"),
    ({'pieces': [STRAIGHT, {'type': 'tee', 'enter': 'run', 'side': 'left', 'leave': 'branch'},
                 {'type': 'straight', 'length_mm': 100}, {'type': 'mitre', 'turn': 'left'},
                 {'type': 'straight', 'length_mm': 100}, {'type': 'mitre', 'turn': 'left'},
                 {'type': 'straight', 'length_mm': 600}]}, 'pieces[6]', 'overlaps pieces[0]'),
    ({'pieces': [STRAIGHT], 'obstacles': [{'type': 'step', 'at_mm': 900, 'height_mm': 3}]},
     'obstacles[0]', 'outside the network'),
    ({'pieces': [STRAIGHT], 'obstacles': [{'type': 'boulder', 'at_mm': 100}]}, 'obstacles[0]', 'unknown element'),
    ({'pieces': [STRAIGHT], 'start': {'at_mm': 800}}, 'start', 'not inside a straight'),
    ({'pieces': []}, 'pieces', 'non-empty'),
    ({'pipes': [STRAIGHT]}, 'top-level', 'unknown'),
    ({'pieces': [STRAIGHT], 'pipe': {'outer_mm': 90}}, 'pipe', 'wall_mm or sdr'),
    ({'pieces': [STRAIGHT], 'pipe': {'outer_mm': 90, 'sdr': 26, 'wall_mm': 3.5}}, 'pipe', 'wall_mm or sdr'),
    ({'pieces': [STRAIGHT], 'pipe': {'outer_mm': 110, 'sdr': 26}}, 'pipe', 'must be the size'),
    ({'pieces': [STRAIGHT, dict(STRAIGHT, diameter_mm=110)], 'pipe': {'outer_mm': 90, 'sdr': 26}}, 'pipe',
     'must be the size'),
    ({'pieces': [STRAIGHT], 'pipe': {'outer_mm': 90, 'wall_mm': 'thick'}}, 'pipe', 'not a number'),
    ({'pieces': [STRAIGHT], 'pipe': {'outer_mm': 90, 'sdr': 25}}, 'pipe', 'sdr 25 is not a standard series'),
    ({'pieces': [STRAIGHT], 'pipe': {'outer_mm': 90, 'wall_mm': 15}}, 'pipe', 'robot fits in'),
])
def test_bad_world_is_refused_with_file_entry_and_reason(data, entry, reason, tmp_path):
    message = _refusal(data, tmp_path)
    assert 'bad.yaml' in message and entry in message and reason in message, message


def test_unreadable_file_is_refused(tmp_path):
    path = tmp_path / 'broken.yaml'
    path.write_text('pieces: [ {type: straight')
    with pytest.raises(network.WorldError, match='broken.yaml: cannot read'):
        network.load(str(path))


@pytest.mark.parametrize('outer', [90, 110])
def test_every_standard_wall_is_about_its_outer_diameter_over_its_ratio(outer):
    """The listed walls are ISO 4065's: outer / SDR rounded up, within a tenth and a rounding of the series."""
    for sdr, wall in network.STANDARD_WALLS_MM[outer].items():
        assert outer / sdr - 0.05 <= wall <= outer / sdr + 0.15, (outer, sdr, wall)


def test_a_world_of_a_real_pipe_keeps_its_size_for_the_layout_and_says_its_bore(tmp_path):
    sdr26 = network.load(os.path.join(WORLDS, 'straight_90_sdr26.yaml'))
    nominal = network.load(os.path.join(WORLDS, 'straight_90.yaml'))
    assert sdr26.bore_offset_m == pytest.approx(-0.007) and nominal.bore_offset_m == 0.0
    assert sdr26.diameter_at(0.4) == nominal.diameter_at(0.4) == pytest.approx(0.09)
    assert [p.exit.origin for p in sdr26.pieces] == [p.exit.origin for p in nominal.pieces]
    path = tmp_path / 'walled.yaml'
    path.write_text(yaml.safe_dump({'pieces': [STRAIGHT], 'pipe': {'outer_mm': 90, 'wall_mm': 2.7}}))
    assert network.load(str(path)).bore_offset_m == pytest.approx(-0.0054)
