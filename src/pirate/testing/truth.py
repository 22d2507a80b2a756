"""Where the twin says the robot is along a pipe map: for tests and
bench/mission_sweep only, to judge the executive's estimate. Never used by
the executive (the real robot has no ground truth).

The robot's middle is the midpoint of the rotational module's two bodies
(the point a world's ``start`` and the planner's positions refer to),
projected on the path axis (:meth:`pirate.world.network.Network.nearest_along`).
"""
from pirate.sim.twin_robot import ROOT, ROTATIONAL_FRONT


def middle(truth):
    """World position (m) of the robot's middle in a twin ground truth dict."""
    a, b = truth['poses'][ROOT][0], truth['poses'][ROTATIONAL_FRONT][0]
    return tuple((x + y) / 2.0 for x, y in zip(a, b))


def robot_along_m(pipe_map, truth):
    """Where the twin's robot middle is along ``pipe_map``, m."""
    return pipe_map.nearest_along(middle(truth))


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
