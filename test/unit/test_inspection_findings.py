"""Where a finding is: the mark service's position computation (pure)."""
import math

import pytest

from pirate.inspection import findings as fd
from pirate.world import network

UPRIGHT = math.pi / 2


@pytest.fixture(scope='module')
def pipe_map():
    return network.load(network.world_path('inspection_network_90'))


@pytest.mark.parametrize('pan, tilt, roll, hours', [
    (0.0, 0.5, UPRIGHT, 12.0),              # looking up, upright: the crown
    (0.0, -0.5, UPRIGHT, 6.0),              # looking down: the invert
    (0.5, 0.0, UPRIGHT, 9.0),               # looking left
    (-0.5, 0.0, UPRIGHT, 3.0),              # looking right
    (0.0, 0.5, 0.0, 3.0),                   # looking up, lying on its right side: the right wall
    (0.0, 0.5, math.pi, 9.0),               # looking up, lying on its left side: the left wall
    (0.5, 0.5, UPRIGHT, 10.5),              # up and left
])
def test_the_clock_position_follows_pan_tilt_and_roll(pan, tilt, roll, hours):
    assert fd.clock_position(pan, tilt, roll) == pytest.approx(hours, abs=0.6)


def test_a_camera_along_the_pipe_gives_no_clock_position():
    assert fd.clock_position(0.0, 0.0, UPRIGHT) is None
    assert fd.clock_text(None).startswith('ahead')


@pytest.mark.parametrize('hours, text', [(12.0, "12 o'clock"), (10.1, "10 o'clock"), (2.4, 'half past 2'),
                                         (0.2, "12 o'clock")])
def test_clock_text(hours, text):
    assert fd.clock_text(hours) == text


def test_a_finding_past_the_first_bend_is_placed_from_the_launch_pit_and_the_bend(pipe_map):
    launch = pipe_map.points['launch_pit']      # 0.4 m; the first bend is 1.2..1.29 m
    where = fd.position_on_map(pipe_map, 1.5, launch, 0.2, 0.0, 0.5, UPRIGHT)
    assert where['from_launch_pit_mm'] == pytest.approx(1100)
    assert where['segment'] == 'pipe_2'
    assert where['last_junction'] == 'mitre_1'
    assert where['from_last_junction_mm'] == pytest.approx(1500 - 1290)
    assert where['uncertainty_mm'] == pytest.approx(200)
    assert where['clock_text'] == "12 o'clock"


def test_a_finding_before_any_junction_counts_from_the_start_of_the_map(pipe_map):
    where = fd.position_on_map(pipe_map, 0.3, 0.4, 0.15, 0.0, 0.0, UPRIGHT)
    assert (where['segment'], where['last_junction'], where['from_last_junction_mm']) == (
        'pipe_1', 'the start of the map', pytest.approx(300))
    assert where['from_launch_pit_mm'] == pytest.approx(100)      # behind the launch pit still counts
    assert where['clock'] is None


def test_a_finding_off_the_map_is_refused(pipe_map):
    with pytest.raises(fd.FindingError, match='off the map'):
        fd.position_on_map(pipe_map, pipe_map.length + 0.1, 0.4, 0.1, 0.0, 0.0, UPRIGHT)


def test_an_unknown_kind_is_refused_with_the_known_ones():
    assert fd.check_kind(' Leak ') == 'leak' and fd.check_kind('') == 'other'
    with pytest.raises(fd.FindingError, match='displaced_joint'):
        fd.check_kind('hole')


def test_the_dig_list_is_sorted_from_the_launch_pit(pipe_map):
    marked = [{'number': n, 'position': fd.position_on_map(pipe_map, along, 0.4, 0.1, 0, 0, UPRIGHT)}
              for n, along in ((1, 3.0), (2, 1.0), (3, 2.0))]
    listed = fd.dig_list(marked + [dict(marked[1], number=4, kind=fd.VIEW)])    # a view is no place to dig
    assert [f['number'] for f, _ in listed] == [2, 3, 1]
    assert listed[0][1].startswith('dig at 0.60 m (+/- 0.10 m) from the launch pit along the route')
