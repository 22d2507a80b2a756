"""plot_run on a bag written here (no master): the bag layer reads states,
feedback and goals, and the command draws one marker per primitive."""
import math
import os

import pytest

rosbag = pytest.importorskip('rosbag', reason='rosbag missing (Debian python3-rosbag)')
import rospy  # noqa: E402
from pirate.msg import (PirateActionFeedback, PirateActionGoal, PirateActionResult,  # noqa: E402
                        PrimitiveStep, RobotState)

from pirate import names
from pirate.robot import tables  # noqa: E402
from pirate.viz import bag_ros, plot_cli  # noqa: E402

RESULTS = os.path.join(os.path.dirname(__file__), '..', '..', 'test-results')
PRIMITIVES = ('move front', 'clamp rear', 'clamp front')


def _write(path):
    with rosbag.Bag(path, 'w') as out:
        t0 = 100.0
        goal = PirateActionGoal()
        goal.goal_id.id = 'g1'
        goal.goal.pipe_diameter = 90
        out.write(names.PIRATE_ACTION + '/goal', goal, rospy.Time.from_sec(t0))
        for i in range(60):
            t = t0 + 0.1 + i * 0.1
            state = RobotState()
            state.name = list(tables.JOINT_NAMES)
            state.position = [-0.01 * i if j == 'bend_i' else 0.0 for j in tables.JOINT_NAMES]
            state.effort = [1.0] * len(tables.JOINT_NAMES)
            state.orientation = math.pi / 2
            out.write(names.ROBOT_STATE_TOPIC, state, rospy.Time.from_sec(t))
            feedback = PirateActionFeedback()
            feedback.status.goal_id.id = 'g1'
            feedback.feedback.primitive = PRIMITIVES[i // 20] if i % 20 < 18 else ''
            out.write(names.PIRATE_ACTION + '/feedback', feedback, rospy.Time.from_sec(t))


def test_read_run(tmp_path):
    path = str(tmp_path / 'run.bag')
    _write(path)
    run, diameters = bag_ros.read_run(path)
    assert diameters == [90]
    assert len(run.times) == 60 and run.times[0] == 0.0
    assert run.positions['bend_i'][10] == pytest.approx(-0.1)
    assert [p for _, p in run.markers] == list(PRIMITIVES)
    assert [t for t, _ in run.markers] == pytest.approx([0.0, 2.0, 4.0])


def test_a_primitive_recorded_before_the_first_state_is_at_zero(tmp_path):
    path = str(tmp_path / 'run.bag')
    with rosbag.Bag(path, 'w') as out:
        feedback = PirateActionFeedback()
        feedback.status.goal_id.id = 'g1'
        feedback.feedback.primitive = 'move front'
        out.write(names.PIRATE_ACTION + '/feedback', feedback, rospy.Time.from_sec(50.0))
        state = RobotState()
        state.name = list(tables.JOINT_NAMES)
        state.position = [0.0] * len(tables.JOINT_NAMES)
        state.effort = [0.0] * len(tables.JOINT_NAMES)
        out.write(names.ROBOT_STATE_TOPIC, state, rospy.Time.from_sec(50.25))
    run, _ = bag_ros.read_run(path)
    assert run.markers == [(0.0, 'move front')]
    assert run.times == [pytest.approx(0.25)]


def test_plot_run_command(tmp_path, capsys):
    path = str(tmp_path / 'run.bag')
    _write(path)
    os.makedirs(RESULTS, exist_ok=True)
    png = os.path.join(RESULTS, 'plot_run_synthetic_bag.png')
    plot_cli.main([path, '-o', png])
    out = capsys.readouterr().out
    assert out.count(' s  ') == len(PRIMITIVES)
    assert 'guards: ' in out and 'guards_90.yaml' in out
    with open(png, 'rb') as f:
        assert f.read(4) == b'\x89PNG'


def test_plot_run_refuses_a_bag_without_state(tmp_path):
    path = str(tmp_path / 'empty.bag')
    with rosbag.Bag(path, 'w'):
        pass
    with pytest.raises(SystemExit, match='no /pirate/state'):
        plot_cli.main([path, '-o', str(tmp_path / 'x.png')])


def test_plot_run_refuses_a_file_that_is_no_bag(tmp_path):
    path = tmp_path / 'not.bag'
    path.write_text('hello')
    with pytest.raises(SystemExit, match='plot_run'):
        plot_cli.main([str(path), '-o', str(tmp_path / 'x.png')])


def test_markers_from_the_trace_events_and_title(tmp_path):
    """The result's trace wins over lossy feedback; a cancel is an event; the title says what ran."""
    path = str(tmp_path / 'run.bag')
    _write(path)
    with rosbag.Bag(path, 'a') as out:
        result = PirateActionResult()
        result.status.status = 2        # PREEMPTED
        result.result.message = 'Clamp Straight cancelled during clamping front'
        result.result.primitives = [PrimitiveStep(name=n, start=100.1 + 2.0 * i, end=100.1 + 2.0 * i + 1.5)
                                    for i, n in enumerate(('move front', 'clamp rear', 'clamp front', 'x'))]
        out.write(names.PIRATE_ACTION + '/result', result, rospy.Time.from_sec(106.5))
    run, _ = bag_ros.read_run(path)
    assert [p for _, p in run.markers] == ['move front', 'clamp rear', 'clamp front', 'x']
    assert [t for t, _ in run.markers] == pytest.approx([0.0, 2.0, 4.0, 6.0], abs=1e-6)
    assert run.events == [(pytest.approx(6.4), 'cancelled: Clamp Straight cancelled during clamping front')]
    assert run.title.startswith('Clamp Straight - 90 mm pipe - cancelled - run.bag')
    assert len(run.odometry) == len(run.velocity) == len(run.times)
