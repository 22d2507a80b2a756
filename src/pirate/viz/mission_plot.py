"""A mission's run: distance along the route against time, each PAB marked.

The executive publishes its estimate of where the robot
is along the map (``names.MISSION_ALONG_TOPIC``, mm, 5 Hz); the Pirate
Server's goals say which PAB ran when (every goal sent, re-clamps and
retries too); the mission's feedback says when it paused and its result
how it ended. Drawn with pirate.viz.plot's renderer: one panel, a line
tN at each PAB (named in the key), red dashed lines at pauses and at the
end, and the route's named points (the mission goal's map) as dotted
levels, so a drive that stopped short of its target shows.

pirate.viz.bag_ros reads the bag; ``mission_run``, ``panel`` and
``plot_mission`` take plain data, so a test checks what was drawn.
"""
import collections

from pirate import names
from pirate.sequencer.goals import OPTION_NAMES
from pirate.supervisory import planner
from pirate.supervisory.executive import WAIT_RESUME
from pirate.viz import plot
from pirate.viz.plot import PAB_NAMES
from pirate.world import network

ALONG_TOPIC = names.MISSION_ALONG_TOPIC
GOAL_TOPIC = names.MISSION_ACTION + '/goal'
FEEDBACK_TOPIC = names.MISSION_ACTION + '/feedback'
RESULT_TOPIC = names.MISSION_ACTION + '/result'
PAB_GOAL_TOPIC = names.PIRATE_ACTION + '/goal'
TOPICS = (ALONG_TOPIC, GOAL_TOPIC, FEEDBACK_TOPIC, RESULT_TOPIC, PAB_GOAL_TOPIC)

#: A mission's run: ``times`` s and ``along_mm`` (the estimate); ``markers``
#: [(t s, 'PAB ...')]; ``events`` [(t s, 'paused ...' / 'mission ...')];
#: ``points`` [(name, mm along the map)]; ``title`` text; ``junctions``
#: [(what, mm along the map)] of the map's bends and tees.
MissionRun = collections.namedtuple('MissionRun', 'times along_mm markers events points title junctions',
                                    defaults=((),))


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
    route = _route(recorded[GOAL_TOPIC], results)
    return MissionRun([t - t0 for t, _ in along], [msg.data for _, msg in along], markers, sorted(events),
                      route_points(route), mission_title(route, results), route_junctions(route))


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
    """(map, [points]) from the mission goal, or from the plan in its result
    (a recorder can miss a goal sent right after its client connected)."""
    if mission_goals:
        goal = mission_goals[-1][1].goal
        return goal.map, list(goal.points)
    plans = [msg.result.plan for _, msg in results if msg.result.plan]
    return planner.route_of(plans[-1]) if plans else None


def route_points(route):
    """[(name, mm)] of the route's points on its map; [] when it cannot be read."""
    if route is None:
        return []
    try:
        pipe_map = network.load(network.world_path(route[0]))
    except (network.WorldError, OSError):
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


def route_junctions(route):
    """:func:`junctions` of the route's map; () when it cannot be read."""
    if route is None:
        return ()
    try:
        return junctions(network.load(network.world_path(route[0])))
    except (network.WorldError, OSError):
        return ()


def mission_title(route, results):
    text = '%s: %s' % (route[0], planner.ROUTE_JOIN.join(route[1])) if route else 'a mission'
    ends = [msg.result.status for _, msg in results]
    return 'Mission %s%s' % (text, ' (%s)' % ', '.join(ends) if ends else '')


def panel(run):
    """The one :class:`pirate.viz.plot.Panel`: the estimate, the route's points
    (dotted levels) and the map's junctions (dashed grey levels)."""
    return plot.Panel('Distance along the route (the executive\'s estimate)', 'along the map [mm]',
                      [('estimate', run.times, run.along_mm)],
                      [('%s at %.0f mm' % (what, mm), mm) for what, mm in run.junctions], [],
                      [(name, mm) for name, mm in run.points])


def plot_mission(run, path, title=None, xlim=None):
    """Draw ``run`` to the PNG ``path`` (``xlim``: the run plot's time axis); return the panel drawn."""
    drawn = panel(run)
    plot.render([drawn], run.markers, path, title or run.title, run.events, xlim=xlim)
    return drawn
