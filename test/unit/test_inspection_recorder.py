"""The findings recorder: a mark placed where the robot is, with its frames;
findings survive the recorder's death (a new one reads them all back)."""
import json
import math
import os

import pytest

from pirate.inspection import findings as fd
from pirate.inspection import recorder as rec
from pirate.inspection import store
from pirate.supervisory.plan_cli import load_settings
from pirate.world import network

import inspection_run

SETTINGS = {'locate_tolerance_mm': 150, 'odometry_drift': 0.05}
JOINTS = ['camera_tilt', 'camera_pan']


def _frame(colour, stamp_s=1.0):
    width, height = 8, 6
    return rec.Frame(width, height, 'rgb8', width * 3, bytes(colour) * (width * height), stamp_s)


def _recorder(folder, settings=SETTINGS):
    pipe_map = network.load(network.world_path(inspection_run.MAP))
    launch_m = pipe_map.points['launch_pit']
    recorder = rec.Recorder(store.RunStore(folder, {'map': inspection_run.MAP, 'launch_pit_mm': launch_m * 1000}),
                            settings)
    recorder.set_map(pipe_map, launch_m)
    return recorder


def test_the_settings_the_node_uses_have_what_the_recorder_needs(tmp_path):
    _recorder(str(tmp_path), load_settings()[0]).where()


def test_before_any_estimate_the_robot_is_at_the_launch_pit_then_follows_its_odometry(tmp_path):
    recorder = _recorder(str(tmp_path))
    recorder.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 5000.0)
    assert recorder.where() == pytest.approx((0.4, 0.15))
    recorder.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 5600.0)
    assert recorder.where() == pytest.approx((1.0, 0.15 + 0.05 * 0.6))


def test_the_missions_estimate_re_anchors_and_the_way_back_counts_down(tmp_path):
    recorder = _recorder(str(tmp_path))
    recorder.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 9000.0)
    recorder.uncertainty(180.0)
    recorder.estimate(3200.0)
    assert recorder.where() == pytest.approx((3.2, 0.18))
    recorder.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 8000.0)      # 1 m back towards the launch pit
    assert recorder.where() == pytest.approx((2.2, 0.18 + 0.05))


def test_a_mark_records_the_place_the_clock_and_both_frames(tmp_path):
    recorder = _recorder(str(tmp_path))
    recorder.robot_state(JOINTS, [0.5, 0.0], math.pi / 2, 0.0)       # tilted up: 12 o'clock
    recorder.estimate(1500.0)
    recorder.frame('front', _frame((255, 0, 0)))
    recorder.frame('rear', _frame((0, 255, 0)))
    finding = recorder.mark('Leak', 'hiss', 12.5, 'service')
    assert finding['kind'] == 'leak' and finding['number'] == 1
    assert finding['position']['from_launch_pit_mm'] == pytest.approx(1100)
    assert finding['position']['segment'] == 'pipe_2' and finding['position']['clock_text'] == "12 o'clock"
    assert sorted(finding['frames']) == ['front', 'rear'] and finding['no_frame'] == {}


def test_a_camera_without_a_frame_is_said_and_the_finding_kept(tmp_path):
    recorder = _recorder(str(tmp_path))
    recorder.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 0.0)
    recorder.frame('front', rec.Frame(8, 6, 'yuv422', 16, b'', 1.0))
    finding = recorder.mark('other', '', 1.0, 'panel')
    assert finding['frames'] == {}
    assert 'yuv422' in finding['no_frame']['front'] and 'none received' in finding['no_frame']['rear']


def test_no_map_and_a_bad_kind_are_refused_and_nothing_is_written(tmp_path):
    recorder = rec.Recorder(store.RunStore(str(tmp_path)), SETTINGS)
    with pytest.raises(fd.FindingError, match='no map'):
        recorder.mark('leak', '', 0.0, 'service')
    with pytest.raises(fd.FindingError, match='not one of'):
        _recorder(str(tmp_path)).mark('hole', '', 0.0, 'service')
    assert store.read_findings(str(tmp_path), missing_ok=True)[0] == []


def test_an_estimate_heard_before_the_map_is_no_map_to_mark_on(tmp_path):
    """The mission's estimate can come before its map (make demo): the mark is refused with the reason."""
    recorder = rec.Recorder(store.RunStore(str(tmp_path)), SETTINGS)
    recorder.estimate(800.0)
    with pytest.raises(fd.FindingError, match='no map'):
        recorder.mark('leak', '', 0.0, 'service', where=None)
    with pytest.raises(fd.FindingError, match='no map'):
        recorder.where()


def test_an_estimate_heard_before_the_map_stands_when_the_map_comes(tmp_path):
    """A recorder started late hears the estimate, then the latched mission
    and its map: the robot is where the estimate says, not at the launch pit;
    another map starts from its launch pit."""
    pipe_map = network.load(network.world_path(inspection_run.MAP))
    recorder = rec.Recorder(store.RunStore(str(tmp_path)), SETTINGS)
    recorder.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 100.0)
    recorder.estimate(800.0)
    recorder.set_map(pipe_map, pipe_map.points['launch_pit'])
    assert recorder.where()[0] == pytest.approx(0.8)
    other = network.load(network.world_path('straight_90'))
    recorder.set_map(other, other.start_m)
    assert recorder.where()[0] == pytest.approx(other.start_m)


def test_findings_survive_the_recorders_death(tmp_path):
    folder = str(tmp_path / 'run')
    recorder = _recorder(folder)
    recorder.robot_state(JOINTS, [0.0, 0.6], math.pi / 2, 0.0)
    recorder.frame('front', _frame((9, 9, 9)))
    for note in ('one', 'two'):
        recorder.mark('deposit', note, 1.0, 'panel')
    del recorder                                    # the node died
    again = _recorder(folder)
    again.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 0.0)
    again.mark('water', 'three', 2.0, 'service')
    found, warnings = store.read_findings(folder)
    assert [(f['number'], f['note']) for f in found] == [(1, 'one'), (2, 'two'), (3, 'three')] and not warnings


def test_the_missions_uncertainty_arriving_after_its_estimate_still_counts(tmp_path):
    recorder = _recorder(str(tmp_path))
    recorder.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 0.0)
    recorder.estimate(2000.0)
    recorder.uncertainty(230.0)
    assert recorder.where() == pytest.approx((2.0, 0.23))


def test_the_missions_heard_make_the_runs_timeline(tmp_path):
    folder = str(tmp_path)
    recorder = _recorder(folder)
    recorder.mission_goal(1.0, 'inspection_network_90', ['launch_pit', 'target'], 'goal-1')
    recorder.mission_goal(1.0, 'inspection_network_90', ['launch_pit', 'target'], 'goal-1')   # latched: heard again
    for stamp, step, state in ((2.0, 1, 'running'), (3.0, 1, 'running'), (9.0, 2, 'waiting')):
        recorder.mission_feedback(stamp, step, 9, 'DRIVE', '', 600.0, state, 'resume' if state == 'waiting' else '')
    recorder.mission_result(20.0, 'succeeded', '9 PABs')
    with open(os.path.join(folder, store.TIMELINE_FILE)) as stream:
        texts = [json.loads(line)['text'] for line in stream]
    assert texts == ['mission sent: inspection_network_90, launch_pit -> target', 'step 1/9: DRIVE, running',
                     'step 2/9: DRIVE, waiting for resume', 'mission succeeded: 9 PABs']
    restarted = rec.Recorder(store.RunStore(folder), SETTINGS)      # a restarted node hears it latched
    restarted.mission_goal(1.0, 'inspection_network_90', ['launch_pit', 'target'], 'goal-1')
    restarted.mission_goal(30.0, 'inspection_network_90', ['target', 'launch_pit'], 'goal-2')
    with open(os.path.join(folder, store.TIMELINE_FILE)) as stream:
        texts = [json.loads(line)['text'] for line in stream]
    assert texts[4:] == ['mission sent: inspection_network_90, target -> launch_pit']


def test_a_mark_keeps_the_place_it_was_asked_at_and_no_frame_of_the_last_mark(tmp_path):
    recorder = _recorder(str(tmp_path))
    recorder.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 0.0)
    recorder.frame('front', _frame((1, 2, 3)))
    recorder.mark('other', 'first', 1.0, 'panel')
    asked = recorder.where()
    recorder.robot_state(JOINTS, [0.0, 0.0], math.pi / 2, 200.0)      # moved while the frames came
    recorder.forget_frames()
    finding = recorder.mark('other', 'second', 2.0, 'panel', where=asked)
    assert finding['position']['from_launch_pit_mm'] == pytest.approx(0.0) and finding['frames'] == {}
