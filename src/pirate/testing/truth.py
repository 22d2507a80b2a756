"""Where the twin says the robot is along a pipe map: for tests and
bench/mission_sweep only, to judge the executive's estimate. Never used by
the executive (the real robot has no ground truth).

The robot's middle is the midpoint of the rotational module's two bodies
(the point a world's ``start`` and the planner's positions refer to),
projected on the path axis.
"""
from pirate.sim.twin_robot import ROOT, ROTATIONAL_FRONT

PROJECT_STEP_M = 0.005
FINE_STEPS = 50


def middle(truth):
    """World position (m) of the robot's middle in a twin ground truth dict."""
    a, b = truth['poses'][ROOT][0], truth['poses'][ROTATIONAL_FRONT][0]
    return tuple((x + y) / 2.0 for x, y in zip(a, b))


def along_m(pipe_map, position):
    """The path position (m) nearest to ``position`` (world, m): every 5 mm,
    then to 0.1 mm around the best."""
    def dist(along):
        origin = pipe_map.locate(along)[1].origin
        return sum((a - b) ** 2 for a, b in zip(origin, position))
    coarse = min((i * PROJECT_STEP_M for i in range(int(pipe_map.length / PROJECT_STEP_M) + 1)), key=dist)
    fine = [coarse + (i - FINE_STEPS) * PROJECT_STEP_M / FINE_STEPS for i in range(2 * FINE_STEPS + 1)]
    return min((a for a in fine if 0.0 <= a <= pipe_map.length), key=dist)


def robot_along_m(pipe_map, truth):
    """Where the twin's robot middle is along ``pipe_map``, m."""
    return along_m(pipe_map, middle(truth))


def on_pab_state(harness, server_state, pab_state, action):
    """Call ``action()`` once, the first time the PAB ``server_state`` (e.g.
    'Taking T-joint') of a pirate.testing.harness.SimHarness enters ``pab_state``,
    in the PAB's own thread as its server reports it (so the twin has not
    moved on): to read the truth where a junction was sensed, or to pause
    there."""
    seen = []

    def call(feedback):
        if feedback.server_state == server_state and feedback.pab_state == pab_state and not seen:
            seen.append(pab_state)
            action()
    _on_feedback(harness, call)


def on_each_pab_state(harness, pab_states, action):
    """Call ``action()`` each time a PAB of a pirate.testing.harness.SimHarness
    enters one of ``pab_states`` (every goal, every junction), in the PAB's
    own thread as its server reports it."""
    last = [None]

    def call(feedback):
        entered = feedback.pab_state != last[0]
        last[0] = feedback.pab_state
        if entered and feedback.pab_state in pab_states:
            action()
    _on_feedback(harness, call)


def _on_feedback(harness, call):
    """Have ``call(feedback)`` see every feedback the harness's server reports, after it is reported."""
    report = harness.server._feedback

    def hook(feedback):
        report(feedback)
        call(feedback)
    harness.server._feedback = hook
