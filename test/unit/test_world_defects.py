"""Defects in the world format: where they lie, and every bad entry refused
with the file, the entry and the reason."""
import math

import pytest

from pirate.world import network

PIECES = [{'type': 'straight', 'length_mm': 1000}, {'type': 'mitre', 'turn': 'left'},
          {'type': 'straight', 'length_mm': 600}, {'type': 'cap'}]


def _world(*defects):
    return network.build({'name': 'w', 'pieces': PIECES, 'defects': list(defects)}, source='w.yaml')


def _defect(**changes):
    spec = {'type': 'leak', 'segment': 1, 'at_mm': 300, 'clock': 10, 'size_mm': 12}
    spec.update(changes)
    return spec


def test_a_defect_lies_in_its_segment_at_its_distance_along_the_path():
    world = _world(_defect())
    defect, = world.defects
    assert (defect.kind, defect.segment, defect.piece) == ('leak', 1, 2)
    assert math.isclose(defect.at, 0.3) and math.isclose(defect.size, 0.012)
    assert math.isclose(defect.along, 1.0 + 0.09 + 0.3)     # first straight, the mitre, 300 mm on


@pytest.mark.parametrize('clock, direction', [(12, (0, 0, 1)), (3, (0, -1, 0)), (6, (0, 0, -1)), (9, (0, 1, 0))])
def test_clock_positions_are_seen_looking_along_the_travel_direction(clock, direction):
    axes = ((1, 0, 0), (0, 1, 0), (0, 0, 1))
    assert all(abs(a - b) < 1e-9 for a, b in zip(network.clock_direction(axes, clock), direction))


def test_every_kind_an_inspection_looks_for_is_known():
    kinds = ('leak', 'crack', 'corrosion', 'deposit', 'water', 'displaced_joint', 'intruding_branch')
    world = _world(*[_defect(type=kind, size_mm=10) for kind in kinds])
    assert [d.kind for d in world.defects] == list(kinds)


@pytest.mark.parametrize('changes, says', [
    ({'type': 'rust'}, "defects[0]: unknown element 'rust'"),
    ({'at_mm': 700}, 'at_mm 700 is beyond segment 1 (0..600 mm)'),
    ({'at_mm': -1}, 'at_mm -1 is beyond segment 1'),
    ({'segment': 2}, 'segment 2 is not a straight segment (0..1'),
    ({'segment': 'one'}, "segment 'one' is not a straight segment"),
    ({'clock': 13}, 'clock 13 is not a clock position (1-12'),
    ({'clock': 0}, 'clock 0 is not a clock position'),
    ({'clock': 'ten'}, "clock 'ten' is not a number"),
    ({'size_mm': 0}, 'size_mm 0 must be > 0'),
    ({'type': 'intruding_branch', 'size_mm': 50}, 'below 45 mm (the pipe radius)'),
    ({'colour': 'red'}, "unknown ['colour']"),
])
def test_a_bad_defect_is_refused_naming_the_file_entry_and_reason(changes, says):
    with pytest.raises(network.WorldError) as refused:
        _world(_defect(**changes))
    assert str(refused.value).startswith('w.yaml: defects[0]')
    assert says in str(refused.value)


def test_a_missing_key_is_named():
    spec = _defect()
    del spec['clock']
    with pytest.raises(network.WorldError, match=r"missing \['clock'\]"):
        _world(spec)


def test_defects_must_be_a_list():
    with pytest.raises(network.WorldError, match='defects: a list'):
        network.build({'pieces': PIECES, 'defects': {'type': 'leak'}}, source='w.yaml')


def test_the_inspection_network_has_a_defect_past_a_bend_behind_the_target():
    world = network.load(network.world_path('inspection_network_90'))
    target = world.points['target']
    bends = [sum(p.length for p in world.pieces[:i]) for i, p in enumerate(world.pieces) if p.kind == 'mitre']
    behind = [d for d in world.defects if bends[-1] < d.along < target]
    assert len(world.defects) >= 5 and behind
