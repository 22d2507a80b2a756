"""The mission plot from a recorded run: distance along
the route against time, each PAB marked, the pause and the end.

test/data/missions/straight_90_pause.bag was recorded by launch/record.launch
with the twin (straight_90, rate 3), pirate_manager, mission_executive and
``run_mission --route straight_90 pit target pit --speed 50``, paused by
the command service during the first drive and resumed; the recording was
cut to its mission and goal topics and every 25th /pirate/state."""
import os

import pytest

rosbag = pytest.importorskip('rosbag', reason='rosbag missing (Debian python3-rosbag)')
import rospy  # noqa: E402
from std_msgs.msg import Float64  # noqa: E402

from pirate import names  # noqa: E402
from pirate.msg import MissionActionGoal, MissionGoal  # noqa: E402
from pirate.supervisory import planner  # noqa: E402
from pirate.viz import bag_ros, mission_plot, plot_cli  # noqa: E402

HERE = os.path.dirname(__file__)
RECORDED = os.path.join(HERE, '..', 'data', 'missions', 'straight_90_pause.bag')
RESULTS = os.path.join(HERE, '..', '..', 'test-results')


@pytest.fixture(scope='module')
def run():
    return bag_ros.read_mission(RECORDED)


def test_every_pab_sent_is_marked_in_order_with_its_distance(run):
    assert [label for _, label in run.markers] == [
        'CLAMP_STRAIGHT', 'DRIVE +500 mm', 'DRIVE +150 mm', 'DRIVE -504 mm', 'HOME']
    times = [t for t, _ in run.markers]
    assert times == sorted(times) and times[0] == pytest.approx(0.0, abs=0.5)


def test_the_pause_and_the_end_are_events_and_the_route_its_levels(run):
    assert [text.split(':')[0] for _, text in run.events] == ['paused at step 2 (DRIVE)', 'mission succeeded']
    assert run.points == [('pit', 400.0), ('target', 900.0)]
    assert run.title == 'Mission straight_90: pit -> target -> pit (succeeded)'


def test_the_estimate_goes_to_the_target_holds_while_paused_and_comes_back(run):
    def along_at(t):
        return min(zip(run.times, run.along_mm), key=lambda ta: abs(ta[0] - t))[1]
    pause_t = run.events[0][0]
    resume_t = run.markers[2][0]
    assert along_at(run.markers[1][0]) == pytest.approx(400, abs=5)          # the first drive starts at pit
    assert max(run.along_mm) == pytest.approx(900, abs=20)                   # reaches the target
    assert along_at(pause_t + 1) == pytest.approx(along_at(resume_t - 1), abs=2)   # held while paused
    assert along_at(run.markers[4][0]) == pytest.approx(400, abs=20)         # back at pit for HOME


def test_plot_run_writes_the_mission_plot_beside_the_run_plot(tmp_path, capsys):
    os.makedirs(RESULTS, exist_ok=True)
    png = os.path.join(RESULTS, 'plot_run_mission_straight_90.png')
    plot_cli.main([RECORDED, '-o', png])
    out = capsys.readouterr().out
    mission_png = png[:-len('.png')] + '_mission.png'
    assert 'wrote %s (Mission straight_90: pit -> target -> pit (succeeded): 5 PABs' % mission_png in out
    with open(mission_png, 'rb') as f:
        assert f.read(4) == b'\x89PNG'


def test_the_panel_draws_the_estimate_and_the_points(run):
    drawn = mission_plot.panel(run)
    assert drawn.series == [('estimate', run.times, run.along_mm)]
    assert drawn.references == [('pit', 400.0), ('target', 900.0)]


def test_a_run_without_a_mission_has_no_mission_plot(tmp_path):
    path = str(tmp_path / 'no_mission.bag')
    with rosbag.Bag(path, 'w') as out:
        out.write(names.ROBOT_STATE_TOPIC + '_other', Float64(data=1.0), rospy.Time.from_sec(1.0))
    assert bag_ros.read_mission(path) is None


@pytest.mark.parametrize('lines, route', [
    (['plan on straight_90: pit -> target -> pit (4 PABs)', '  1. ...'], ('straight_90', ['pit', 'target', 'pit'])),
    (['plan on /a/b: c.yaml: x -> y (2 PABs)'], ('/a/b: c.yaml', ['x', 'y'])),
    ([], None), (['mission refused'], None)])
def test_the_route_is_read_back_from_a_printed_plan(lines, route):
    assert planner.route_of(lines) == route


def test_the_mission_plot_shares_the_run_plots_time_axis(tmp_path):
    run, _, _, mission = plot_cli.plot_bag_and_mission(RECORDED, str(tmp_path / 'run.png'))
    assert os.path.exists(str(tmp_path / 'run_mission.png'))
    assert [t for t, _ in mission.markers] == pytest.approx([start for start, _, _ in run.spans], abs=0.05)
    assert [pab for _, _, pab in run.spans] == ['CLAMP_STRAIGHT', 'DRIVE', 'DRIVE', 'DRIVE', 'HOME']
    assert plot_cli.shared_axis(run, mission)[1] >= max(run.times[-1], mission.times[-1])


def test_the_mission_plot_draws_the_maps_junctions():
    from pirate.world import network
    found = mission_plot.junctions(network.load(network.world_path('inspection_network_90')))
    assert found and all(mm > 0 for _, mm in found)
    run = mission_plot.MissionRun([0.0], [400.0], [], [], [('pit', 400.0)], 't', found)
    assert [value for _, value in mission_plot.panel(run).guards] == [mm for _, mm in found]


def _truth_at(pipe_map, along_m):
    """A ground-truth PoseArray with every body at the path's axis ``along_m`` (m)."""
    from geometry_msgs.msg import Pose, PoseArray
    from pirate.sim.twin_robot import TRUTH_BODIES
    msg = PoseArray()
    for _ in TRUTH_BODIES:
        pose = Pose()
        pose.position.x, pose.position.y, pose.position.z = pipe_map.locate(along_m)[1].origin
        msg.poses.append(pose)
    return msg


@pytest.mark.parametrize('along_m', [
    [0.4, 0.45, 0.5, 1.2, 1.8, 2.1],        # along the main, and a jump past the search window
    [2.1, 1.9, 0.6]])                       # backwards
def test_the_twins_true_position_is_its_middle_projected_on_the_map(along_m):
    from pirate.world import network
    pipe_map = network.load(network.world_path('inspection_tee_90'))
    truth = [(0.3 * k, _truth_at(pipe_map, a)) for k, a in enumerate(along_m)]
    times, mm = mission_plot.true_along(pipe_map, truth)
    assert times == pytest.approx([0.3 * k for k in range(len(along_m))])
    assert mm == pytest.approx([a * 1000.0 for a in along_m], abs=0.5)


def test_the_true_position_is_drawn_a_sample_every_fifth_of_a_second():
    from pirate.world import network
    pipe_map = network.load(network.world_path('straight_90'))
    truth = [(0.1 * k, _truth_at(pipe_map, 0.4 + 0.01 * k)) for k in range(10)]
    times, _ = mission_plot.true_along(pipe_map, truth)
    assert times == pytest.approx([0.0, 0.2, 0.4, 0.6, 0.8])
    assert mission_plot.true_along(pipe_map, []) == ()


def test_a_run_with_the_twins_ground_truth_draws_the_true_position_beside_the_estimate(run):
    from pirate.world import network
    pipe_map = network.load(network.world_path('straight_90'))
    recorded = {topic: [] for topic in mission_plot.TOPICS}
    recorded[mission_plot.ALONG_TOPIC] = [(10.0 + 0.2 * k, Float64(data=400.0 + 10 * k)) for k in range(5)]
    recorded[mission_plot.TRUTH_TOPIC] = [(10.0 + 0.2 * k, _truth_at(pipe_map, 0.41 + 0.01 * k)) for k in range(5)]
    goal = MissionActionGoal(goal=MissionGoal(map='straight_90', points=['pit', 'target']))
    recorded[mission_plot.GOAL_TOPIC] = [(10.0, goal)]
    drawn = mission_plot.panel(mission_plot.mission_run(recorded))
    assert [label for label, _, _ in drawn.series] == ['estimate', 'true (twin)']
    assert drawn.series[1][2] == pytest.approx([410.0, 420.0, 430.0, 440.0, 450.0], abs=0.5)
    assert 'truth' in drawn.title
    assert not run.truth        # the recorded bag holds no ground truth: the estimate alone


def test_a_resumed_mission_is_drawn_on_the_map_the_executive_latched():
    """A resume goal names no map; the executive's latched current mission does."""
    recorded = {topic: [] for topic in mission_plot.TOPICS}
    recorded[mission_plot.ALONG_TOPIC] = [(10.0 + 0.2 * k, Float64(data=400.0 + 10 * k)) for k in range(5)]
    recorded[mission_plot.GOAL_TOPIC] = [(10.0, MissionActionGoal(goal=MissionGoal(resume=True)))]
    recorded[mission_plot.CURRENT_TOPIC] = [
        (10.1, MissionActionGoal(goal=MissionGoal(map='inspection_network_90', points=['launch_pit', 'target'])))]
    drawn = mission_plot.mission_run(recorded)
    assert [name for name, _ in drawn.points] == ['launch_pit', 'target']
    earlier = MissionActionGoal(goal=MissionGoal(map='straight_90', points=['pit', 'target']))
    recorded[mission_plot.GOAL_TOPIC].insert(0, (5.0, earlier))       # a mission before it: not the one drawn
    assert [name for name, _ in mission_plot.mission_run(recorded).points] == ['launch_pit', 'target']
    recorded[mission_plot.GOAL_TOPIC].pop(0)
    recorded[mission_plot.CURRENT_TOPIC] = []
    assert mission_plot.mission_run(recorded).points == []
