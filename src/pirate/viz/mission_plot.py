"""A mission's run: distance along the route against time, each PAB marked.

The executive publishes its estimate of where the robot
is along the map (``names.MISSION_ALONG_TOPIC``, mm, 5 Hz); the Pirate
Server's goals say which PAB ran when (every goal sent, re-clamps and
retries too); the mission's feedback says when it paused and its result
how it ended. Drawn with pirate.viz.plot's renderer: one panel, a line
tN at each PAB (named in the key), red dashed lines at pauses and at the
end, the route's named points (the mission goal's map) as dotted levels,
so a drive that stopped short of its target shows, and the map's
junctions as dashed levels. When the run is the physics twin's and the bag
holds its ground truth (``names.GROUND_TRUTH_TOPIC``), the true position
of the robot's middle along the map is drawn beside the estimate.

pirate.viz.bag_ros reads the bag; ``mission_run``, ``panel`` and
``plot_mission`` take plain data, so a test checks what was drawn.
"""
import collections

from pirate import names
from pirate.sequencer.goals import OPTION_NAMES
from pirate.supervisory import planner
from pirate.supervisory.executive import WAIT_RESUME
from pirate.viz import plot
from pirate.sim.twin_robot import ROOT, ROTATIONAL_FRONT, TRUTH_BODIES
from pirate.viz.plot import PAB_NAMES
from pirate.world import network

ALONG_TOPIC = names.MISSION_ALONG_TOPIC
GOAL_TOPIC = names.MISSION_ACTION + '/goal'
CURRENT_TOPIC = names.MISSION_CURRENT_TOPIC
FEEDBACK_TOPIC = names.MISSION_ACTION + '/feedback'
RESULT_TOPIC = names.MISSION_ACTION + '/result'
PAB_GOAL_TOPIC = names.PIRATE_ACTION + '/goal'
TRUTH_TOPIC = names.GROUND_TRUTH_TOPIC
TOPICS = (ALONG_TOPIC, CURRENT_TOPIC, GOAL_TOPIC, FEEDBACK_TOPIC, RESULT_TOPIC, PAB_GOAL_TOPIC, TRUTH_TOPIC)
#: The robot's middle: between these two ground-truth poses (their index in TRUTH_BODIES).
MIDDLE_POSES = tuple(TRUTH_BODIES.index(body) for body in (ROOT, ROTATIONAL_FRONT))
#: Simulated s between two true positions drawn (the estimate comes at 5 Hz).
TRUTH_EVERY_S = 0.2

#: A mission's run: ``times`` s and ``along_mm`` (the estimate); ``markers``
#: [(t s, 'PAB ...')]; ``events`` [(t s, 'paused ...' / 'mission ...')];
#: ``points`` [(name, mm along the map)]; ``title`` text; ``junctions``
#: [(what, mm along the map)] of the map's bends and tees; ``truth``
#: ([t s], [mm]) the twin's true position along the map, () without one.
MissionRun = collections.namedtuple('MissionRun', 'times along_mm markers events points title junctions truth',
                                    defaults=((), ()))


def mission_run(recorded, start_s=None):
    """The :data:`MissionRun` in ``recorded`` ({topic in :data:`TOPICS`: [(t s,
    message)]}, as :func:`pirate.viz.bag_ros.read_mission` reads a bag), or
    None if it holds no mission estimate (a run without the mission executive).
    Times from ``start_s`` (the run plot's, so both share the axis), else from
    the mission's first message."""
    along, pab_goals = recorded[ALONG_TOPIC], recorded[PAB_GOAL_TOPIC]
    feedback, results = recorded[FEEDBACK_TOPIC], recorded[RESULT_TOPIC]
    if not along:
        return None
    t0 = start_s if start_s is not None else min(t for t, _ in along + pab_goals + feedback)
    markers = [(t - t0, pab_label(msg.goal)) for t, msg in pab_goals]
    events = [(t - t0, text) for t, text in pauses(feedback)]
    events += [(t - t0, 'mission %s: %s' % (msg.result.status, msg.result.message)) for t, msg in results]
    route = _route(sorted(recorded[CURRENT_TOPIC] + recorded[GOAL_TOPIC], key=lambda heard: heard[0]), results)
    pipe_map = route_map(route)
    truth = true_along(pipe_map, [(t - t0, msg) for t, msg in recorded.get(TRUTH_TOPIC, ())]) if pipe_map else ()
    return MissionRun([t - t0 for t, _ in along], [msg.data for _, msg in along], markers, sorted(events),
                      route_points(route, pipe_map), mission_title(route, results),
                      junctions(pipe_map) if pipe_map else (), truth)


def pab_label(goal):
    """'DRIVE +500 mm', 'MITRE_BEND LEFT', 'HOME' from a Pirate goal."""
    text = PAB_NAMES.get(goal.name, 'PAB %d' % goal.name)
    option = OPTION_NAMES.get(goal.option, 'NONE')
    if option != 'NONE':
        text += ' ' + option
    return text + (' %+.0f mm' % goal.distance if goal.distance else '')


def pauses(feedback):
    """(t, 'paused at step k') each time the mission begins to wait for a resume."""
    out, was = [], False
    for t, msg in feedback:
        now = msg.feedback.waiting_for.startswith(WAIT_RESUME)
        if now and not was:
            out.append((t, 'paused at step %d (%s)' % (msg.feedback.step, msg.feedback.pab)))
        was = now
    return out


def _route(mission_goals, results):
    """(map, [points]) from the last of ``mission_goals`` ([(t s, goal)]: the
    executive's latched current missions and the action's goals, in time)
    that names a map (a resume goal names none; the current mission of a
    resumed one does), or from the plan in its result (a bag of the goal
    topic alone can miss a goal sent right after its client connected)."""
    named = [msg.goal for _, msg in mission_goals if msg.goal.map]
    if named:
        return named[-1].map, list(named[-1].points)
    plans = [msg.result.plan for _, msg in results if msg.result.plan]
    return planner.route_of(plans[-1]) if plans else None


def route_map(route):
    """The route's map (a :class:`pirate.world.network.Network`), or None when it cannot be read."""
    if route is None:
        return None
    try:
        return network.load(network.world_path(route[0]))
    except (network.WorldError, OSError):
        return None


def route_points(route, pipe_map):
    """[(name, mm)] of the route's points on its map; [] without a map."""
    if pipe_map is None:
        return []
    unique = sorted(set(route[1]) & set(pipe_map.points), key=route[1].index)
    return [(name, pipe_map.points[name] * 1000.0) for name in unique]


def junctions(pipe_map):
    """[(what, mm along)] where each piece that is not a straight pipe begins on ``pipe_map``."""
    found, along_m = [], 0.0
    for piece in pipe_map.pieces:
        if piece.kind != 'straight':
            found.append((piece.kind.replace('_', ' '), along_m * 1000.0))
        along_m += piece.length
    return found


def true_along(pipe_map, truth, every_s=TRUTH_EVERY_S):
    """([t s], [mm]): where the twin's robot middle is along ``pipe_map``,
    from ``truth`` [(t s, geometry_msgs/PoseArray of TRUTH_BODIES)], a
    sample every ``every_s``; () without one."""
    times, along_mm, near_m = [], [], None
    for t, msg in truth:
        if times and t - times[-1] < every_s - 1e-9:     # (the stamps' rounding)
            continue
        a, b = (msg.poses[i].position for i in MIDDLE_POSES)
        near_m = pipe_map.nearest_along(((a.x + b.x) / 2, (a.y + b.y) / 2, (a.z + b.z) / 2), near_m)
        times.append(t)
        along_mm.append(near_m * 1000.0)
    return (times, along_mm) if times else ()


def mission_title(route, results):
    text = '%s: %s' % (route[0], planner.ROUTE_JOIN.join(route[1])) if route else 'a mission'
    ends = [msg.result.status for _, msg in results]
    return 'Mission %s%s' % (text, ' (%s)' % ', '.join(ends) if ends else '')


def panel(run):
    """The one :class:`pirate.viz.plot.Panel`: the estimate (and the twin's
    true position when the run has it), the route's points (dotted levels)
    and the map's junctions (dashed grey levels)."""
    series = [('estimate', run.times, run.along_mm)]
    if run.truth:
        series.append(('true (twin)',) + tuple(run.truth))
    return plot.Panel('Distance along the route (%s)' % ('estimate, twin\'s truth' if run.truth else
                                                         'the executive\'s estimate'), 'along the map [mm]', series,
                      [('%s at %.0f mm' % (what, mm), mm) for what, mm in run.junctions], [],
                      [(name, mm) for name, mm in run.points])


def plot_mission(run, path, title=None, xlim=None):
    """Draw ``run`` to the PNG ``path`` (``xlim``: the run plot's time axis); return the panel drawn."""
    drawn = panel(run)
    plot.render([drawn], run.markers, path, title or run.title, run.events, xlim=xlim)
    return drawn
