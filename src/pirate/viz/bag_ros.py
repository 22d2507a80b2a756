"""Read a run's rosbag (launch/record.launch) into a pirate.viz.plot.Run,
and a mission's into a pirate.viz.mission_plot.MissionRun.

The thin layer between rosbag and the plot: joint angles, efforts, the
orientation, odometry and wheel speed from /pirate/state; the primitive
markers from the trace each goal's result carries (robot times, complete
even when feedback was lost), or from the feedback for a bag without
results; cancels and aborts from the results; the pipe diameter and the
title from the goals. Times are in s from the first recorded state,
feedback or primitive start, whichever came first: a recorder that connects
just before a goal can log the first primitive before the first state, and
that marker still belongs on the plot at t >= 0.
"""
import os

import rosbag

from pirate import names
from pirate.viz import mission_plot, plot
from pirate.viz.plot import PAB_NAMES

FEEDBACK_TOPIC = names.PIRATE_ACTION + '/feedback'
GOAL_TOPIC = names.PIRATE_ACTION + '/goal'
RESULT_TOPIC = names.PIRATE_ACTION + '/result'
#: What rosbag raises for a file that is not a readable bag.
BagError = rosbag.ROSBagException
#: actionlib_msgs/GoalStatus codes of the ends the plot marks.
MARKED_ENDS = {2: 'cancelled', 4: 'aborted'}


def read_run(path):
    """(Run, pipe diameters named by the goals, mm) from the bag at ``path``.

    Raises ValueError when the bag holds no robot state to plot.
    """
    states, feedback, goals, results, goal_ids = _read_pirate_topics(path)
    if not states:
        raise ValueError('%s holds no %s messages to plot' % (path, names.ROBOT_STATE_TOPIC))
    found = _primitive_starts(feedback, results)
    t0 = min([states[0][0]] + [t for t, _ in found])
    positions, efforts = _joint_series(states)
    run = plot.Run(times=[t - t0 for t, _ in states], positions=positions, efforts=efforts,
                   orientation=[msg.orientation for _, msg in states],
                   markers=[(t - t0, p) for t, p in found],
                   odometry=[msg.odometry - states[0][1].odometry for _, msg in states],
                   velocity=[msg.velocity for _, msg in states],
                   events=_marked_ends(results, t0), title=run_title(goals, results, path),
                   spans=pab_spans(goals, goal_ids, results, t0), start_s=t0)
    return run, [g.pipe_diameter for _, g in goals if g.pipe_diameter]


def _primitive_starts(feedback, results):
    """[(t s, primitive)]: the results' traces, or the feedback's transitions without them."""
    traced = [(p.start, p.name) for _, msg in results for p in msg.result.primitives]
    return traced if traced else [(t, p) for t, p in plot.transitions(feedback)]


def pab_spans(goals, goal_ids, results, t0):
    """[(start s, end s from ``t0``, PAB)] of each goal from its goal to its result
    (to the last result for one still running when the bag ends)."""
    ended = {msg.status.goal_id.id: t for t, msg in results}
    last = max([t for t, _ in results] + [t for t, _ in goals] + [t0])
    return [(t - t0, ended.get(goal_id, last) - t0, PAB_NAMES.get(goal.name, 'PAB %d' % goal.name))
            for (t, goal), goal_id in zip(goals, goal_ids)]


def _marked_ends(results, t0):
    """[(t s from ``t0``, 'cancelled: ...' / 'aborted: ...')] of the results."""
    return [(t - t0, '%s: %s' % (MARKED_ENDS[msg.status.status], msg.result.message))
            for t, msg in results if msg.status.status in MARKED_ENDS]


def _read_pirate_topics(path):
    """([(t s, RobotState)], [(t s, goal id, primitive)], [(t s, PirateGoal)],
    [(t s, PirateActionResult)], [goal id of each goal]) recorded in the bag at ``path``."""
    states, feedback, goals, results, goal_ids = [], [], [], [], []
    with rosbag.Bag(path) as bag:
        topics = [names.ROBOT_STATE_TOPIC, FEEDBACK_TOPIC, GOAL_TOPIC, RESULT_TOPIC]
        for topic, msg, t in bag.read_messages(topics=topics):
            if topic == names.ROBOT_STATE_TOPIC:
                states.append((t.to_sec(), msg))
            elif topic == FEEDBACK_TOPIC:
                feedback.append((t.to_sec(), msg.status.goal_id.id, msg.feedback.primitive))
            elif topic == RESULT_TOPIC:
                results.append((t.to_sec(), msg))
            else:
                goals.append((t.to_sec(), msg.goal))
                goal_ids.append(msg.goal_id.id)
    return states, feedback, goals, results, goal_ids


def _joint_series(states):
    """({joint: [rad]}, {joint: [mNm]}) for the joints the first state names;
    NaN where a later state lacks one."""
    joints = list(states[0][1].name)
    positions = {j: [] for j in joints}
    efforts = {j: [] for j in joints}
    for _, msg in states:
        by_name = dict(zip(msg.name, zip(msg.position, msg.effort)))
        for j in joints:
            position, effort = by_name.get(j, (float('nan'), float('nan')))
            positions[j].append(position)
            efforts[j].append(effort)
    return positions, efforts


def read_mission(path, start_s=None):
    """The :data:`pirate.viz.mission_plot.MissionRun` in the bag at ``path``,
    or None if it holds no mission estimate (a run without the mission executive);
    ``start_s``: the time of t = 0 (the run plot's :attr:`Run.start_s`)."""
    recorded = {topic: [] for topic in mission_plot.TOPICS}
    with rosbag.Bag(path) as bag:
        for topic, msg, t in bag.read_messages(topics=list(mission_plot.TOPICS)):
            recorded[topic].append((t.to_sec(), msg))
    return mission_plot.mission_run(recorded, start_s)


def run_title(goals, results, path):
    """What ran: the goals' PABs (with drive distances), the pipe, how it ended, the bag."""
    steps = []
    for _, goal in goals:
        name = PAB_NAMES.get(goal.name, 'PAB %d' % goal.name).replace('_', ' ').title()
        steps.append('%s %+.0f mm' % (name, goal.distance) if goal.distance else name)
    pipes = sorted({g.pipe_diameter for _, g in goals if g.pipe_diameter})
    ends = [MARKED_ENDS.get(msg.status.status) for _, msg in results]
    parts = [', '.join(steps) or 'no goal recorded']
    if pipes:
        parts.append('/'.join(str(p) for p in pipes) + ' mm pipe')
    if any(ends):
        parts.append(', '.join(sorted({e for e in ends if e})))
    parts.append(os.path.basename(path))
    return ' - '.join(parts)
