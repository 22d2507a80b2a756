"""Read a run's rosbag (launch/record.launch) into a pirate.viz.plot.Run.

The thin layer between rosbag and the plot: joint angles, efforts and the
orientation from /pirate/state, the primitive markers from the Pirate
Server's feedback, the pipe diameter from its goals. Times are the bag's
record times (sim time when the run used /clock), in s from the first
recorded state or feedback, whichever came first: a recorder that connects
just before a goal can log the first primitive before the first state, and
that marker still belongs on the plot at t >= 0.
"""
import rosbag

from pirate import names
from pirate.viz import plot

FEEDBACK_TOPIC = names.PIRATE_ACTION + '/feedback'
GOAL_TOPIC = names.PIRATE_ACTION + '/goal'
#: What rosbag raises for a file that is not a readable bag.
BagError = rosbag.ROSBagException


def read_run(path):
    """(Run, pipe diameters named by the goals, mm) from the bag at ``path``.

    Raises ValueError when the bag holds no robot state to plot.
    """
    states, feedback, diameters = [], [], []
    with rosbag.Bag(path) as bag:
        topics = [names.ROBOT_STATE_TOPIC, FEEDBACK_TOPIC, GOAL_TOPIC]
        for topic, msg, t in bag.read_messages(topics=topics):
            if topic == names.ROBOT_STATE_TOPIC:
                states.append((t.to_sec(), msg))
            elif topic == FEEDBACK_TOPIC:
                feedback.append((t.to_sec(), msg.status.goal_id.id, msg.feedback.primitive))
            elif msg.goal.pipe_diameter:
                diameters.append(msg.goal.pipe_diameter)
    if not states:
        raise ValueError('%s holds no %s messages to plot' % (path, names.ROBOT_STATE_TOPIC))
    t0 = min(states[0][0], feedback[0][0]) if feedback else states[0][0]
    joints = list(states[0][1].name)
    positions = {j: [] for j in joints}
    efforts = {j: [] for j in joints}
    for _, msg in states:
        by_name = dict(zip(msg.name, zip(msg.position, msg.effort)))
        for j in joints:
            position, effort = by_name.get(j, (float('nan'), float('nan')))
            positions[j].append(position)
            efforts[j].append(effort)
    run = plot.Run(times=[t - t0 for t, _ in states], positions=positions, efforts=efforts,
                   orientation=[msg.orientation for _, msg in states],
                   markers=[(t - t0, p) for t, p in plot.transitions(feedback)])
    return run, diameters
