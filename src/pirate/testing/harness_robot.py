"""The executive's robot in one process: the Pirate Server of a SimHarness.

The same contract as the ROS edge's ActionRobot (pirate.supervisory.
executive_node): ``run(step)`` blocks until the goal ends and returns an
:data:`pirate.supervisory.executive.Report` with the odometry the robot
senses; ``cancel()`` from any thread; ``clamped()`` asks the server's
sensed state. Used by the executive-on-the-twin test and by
bench/mission_sweep; it reads only what the real robot reports, never the
twin's ground truth. Each goal is recorded (:data:`Goal`) with its robot
time, so a caller can count the time a retry cost.
"""
import collections

from pirate.sequencer import goals
from pirate.sequencer.clamp_state import IDLE_CLAMPED
from pirate.supervisory.executive import Report, found_at

#: One goal run: the step sent, how it ended, robot seconds it took.
Goal = collections.namedtuple('Goal', 'step status message seconds')


class HarnessRobot(object):
    """``harness``: a started pirate.testing.harness.SimHarness."""

    def __init__(self, harness):
        self.h = harness
        self.goals = []

    def odometry_mm(self):
        view = self.h.feed.latest()
        return None if view is None else view.odometry

    def run(self, step):
        goal = self.h.goal(goals.CODES[step.pab], pipe_diameter=step.pipe_diameter, distance=step.distance_mm,
                           speed=step.speed_mm_s, option=goals.OPTIONS[step.option or 'NONE'])
        started, start_mm = self.h.robot_time, self.odometry_mm()
        refused, outcome = self.h.execute(goal)
        if refused:
            report = Report('rejected', refused, self.odometry_mm(), None, False)
        else:
            report = Report(outcome.status, outcome.message, self.odometry_mm(),
                            found_at(start_mm, outcome.junction_odometry), bool(outcome.junction_missing))
        self.goals.append(Goal(step, report.status, report.message, self.h.robot_time - started))
        return report

    def cancel(self):
        self.h.server.cancel()

    def clamped(self):
        return self.h.server.status() == IDLE_CLAMPED
