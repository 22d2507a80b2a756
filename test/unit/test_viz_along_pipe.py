"""Where RViz draws the robot along its pipe (pirate.viz.along_pipe, pure)."""
import math

import pytest

from pirate.viz import along_pipe


def test_the_base_stands_along_the_pipe_at_its_odometry():
    assert along_pipe.base_along_m(1234.0) == pytest.approx(1.234)
    assert along_pipe.base_along_m(-250.0) == pytest.approx(-0.25)


@pytest.mark.parametrize('odometry', [float('nan'), float('inf'), -float('inf')])
def test_a_non_finite_odometry_is_refused(odometry):
    with pytest.raises(ValueError, match='odometry'):
        along_pipe.base_along_m(odometry)
    with pytest.raises(ValueError, match='odometry'):
        along_pipe.position_text(odometry)


@pytest.mark.parametrize('odometry, centre', [(0.0, 0), (1234.0, 1200), (1260.0, 1300), (-149.0, -100)])
def test_the_drawn_pipe_follows_the_robot_from_ring_to_ring(odometry, centre):
    assert along_pipe.stretch_centre_mm(odometry) == centre


def test_rings_every_100_mm_over_the_stretch_and_a_label_every_metre():
    marks = along_pipe.ring_marks_mm(1200, 2000)
    assert marks == list(range(200, 2201, 100))
    assert along_pipe.metre_labels(marks) == [(1000, '1 m'), (2000, '2 m')]
    behind = along_pipe.ring_marks_mm(-100, 400)
    assert behind == [-300, -200, -100, 0, 100]
    assert along_pipe.metre_labels(behind) == [(0, '0 m')]
    assert along_pipe.metre_labels([-1000]) == [(-1000, '-1 m')]


def test_a_ring_goes_round_the_axis_at_its_place_and_closes():
    segments = along_pipe.ring_segments(0.3, 0.045)
    assert len(segments) == along_pipe.RING_SEGMENTS
    for start, end in segments:
        assert start[0] == end[0] == 0.3
        assert math.hypot(start[1], start[2]) == pytest.approx(0.045)
    assert segments[-1][1] == segments[0][0]


def test_the_text_says_odometry_and_the_mission_estimate_when_there_is_one():
    assert along_pipe.position_text(1234.4) == 'odometry 1234 mm'
    assert along_pipe.position_text(1234.4, 2345.0, 170.2) == (
        'odometry 1234 mm\nalong the map 2345 mm +/- 170 mm')
    assert along_pipe.position_text(10.0, 20.0) == 'odometry 10 mm\nalong the map 20 mm'
    assert along_pipe.position_text(10.0, float('nan'), 5.0) == 'odometry 10 mm'


def test_an_estimate_is_shown_only_while_the_mission_keeps_publishing_it():
    estimate = along_pipe.MissionEstimate(max_age_s=2.0)
    assert estimate.current(0.0) == (None, None)
    estimate.heard_along(2345.0, 10.0)
    estimate.heard_uncertainty(170.0, 10.1)
    assert estimate.current(11.0) == (2345.0, 170.0)
    assert estimate.current(12.05) == (None, 170.0)
    assert estimate.current(12.5) == (None, None)
    # A clock that went back (a bag replayed, simulated time restarted) shows nothing stale.
    assert estimate.current(5.0) == (None, None)
