"""Drive (report 4.7.4.2.2, 5.12): drive a signed distance while clamped.

By odometry, as the report recommends: drive at the goal's speed until the
remaining distance is what the robot covers in ``creep_lead`` s, creep the
rest at ``creep_speed``, stop ``stop_lead`` s early and wait until the
wheels stand still. Only when the robot reports no odometry (NaN) does it
fall back to the report's time-based drive, eq 5.3: t = 2 x / vf.

Bounded independently of the odometry it waits on: while the wheels are
commanded, odometry must gain ``no_progress_mm`` every ``no_progress_s``
of robot time, and the whole drive never runs longer than its planned
profile plus ``time_margin_s``. Clamped half round a corner
(pabs.half_round) it is refused before anything moves: the two parts lie
in different pipes. The details: doc/sequencer.md, "Drive".
"""
import math

from pirate.robot import units
from pirate.sequencer.pabs import half_round
from pirate.sequencer.pabs.base import ALWAYS, END, Pab, PabFailed, StateMachine, Transition
from pirate.sequencer.pabs.wheels import Progress, speed_problem, stop_wheels

DRIVING = 'driving'
STOPPING = 'stopping'

T = Transition
MACHINE = StateMachine(DRIVING, (
    # state   next state  guard
    T(DRIVING,  STOPPING, ALWAYS),
    T(STOPPING, END,      ALWAYS),
))

MIN_WAIT_S = 0.01       # s: a wait past the deadline still checks its guard once


def distance_problem(distance, limit):
    """Why a Drive of ``distance`` mm (signed) is refused, or None: beyond
    +-``limit`` mm, or shorter than the odometry's resolution (one wheel
    encoder count: 0 mm, and -1e-9 mm, are no drive)."""
    if not math.isfinite(distance) or abs(distance) > limit:
        return 'distance %r mm outside [-%.0f, %.0f] mm' % (distance, limit, limit)
    if abs(distance) < units.WHEEL_MM_PER_COUNT:
        return ('distance %r mm is no drive: below the odometry\'s resolution, %.3f mm'
                % (distance, units.WHEEL_MM_PER_COUNT))
    return None


class Drive(Pab):
    """Drive ``goal.distance`` mm (signed) at ``goal.speed`` mm/s."""

    name = 'Drive'
    machine = MACHINE
    requires_clamped = True

    def __init__(self):
        self.start_mm = None
        self.deadline = None
        self.driven = None
        self.method = 'odometry'

    def check(self, goal, view, guards):
        speed = goal.speed or guards.drive['default_speed']
        problem = speed_problem(speed, min(speed, guards.drive['creep_speed']), guards.drive)
        if problem:
            return problem
        problem = distance_problem(goal.distance, guards.drive['max_distance'])
        if problem:
            return 'drive %s' % problem
        return self._corner_refusal(view, guards)

    def _corner_refusal(self, view, guards):
        """Clamped half round a corner (a turn cancelled twice reads Idle
        Clamped there, both parts pressing their walls), the front part's
        wheels drive along the new pipe and the rear's along the old one:
        in the twin the Drive stalled in 0.4 s and aborted naming an end cap."""
        return half_round.refusal(guards, view, self.after, 'Drive', 'the front part would drive along the new '
                                  'pipe and the rear along the old one, against the corner')

    def actions(self):
        return {DRIVING: self._drive, STOPPING: self._stop}

    def _drive(self, ctx):
        distance = ctx.goal.distance
        speed = math.copysign(ctx.goal.speed or ctx.guards.drive['default_speed'], distance)
        view = ctx.feed.latest()
        self.start_mm = view.odometry
        settings = ctx.guards.drive
        creep = math.copysign(min(settings['creep_speed'], abs(speed)), distance)
        fast_mm = abs(distance) - abs(speed) * settings['creep_lead']
        fast_turning, creep_turning = (units.wheel_speed_mm_s(abs(mm_s)) for mm_s in (speed, creep))
        planned_s = max(fast_mm, 0.0) / fast_turning + (abs(distance) - max(fast_mm, 0.0)) / creep_turning
        self.deadline = view.stamp + planned_s + settings['time_margin_s']   # robot time, both phases
        ctx.prims.drive_at_velocity(speed)
        if math.isnan(view.odometry):
            self.method = 'time (eq 5.3)'
            end = view.stamp + 2.0 * abs(distance) / abs(speed)
            ctx.prims.wait_for('drive by time', lambda v: v.stamp >= end,
                               'robot time %.1f s (eq 5.3)' % (end - view.stamp),
                               end - view.stamp + settings['time_margin_s'])
            return
        if fast_mm > 0:
            self._drive_until(ctx, 'drive', fast_mm)
        ctx.prims.drive_at_velocity(creep)
        self._drive_until(ctx, 'drive creep', abs(distance) - abs(creep) * settings['stop_lead'])

    def _drive_until(self, ctx, name, covered_mm):
        """Wait until the odometry has covered ``covered_mm`` from the start,
        within what is left of the drive's time bound."""
        timeout = max(self.deadline - ctx.feed.latest().stamp, MIN_WAIT_S)
        progress = Progress(ctx.guards.drive, ctx.feed.latest())
        covered = lambda v: progress.check(v) and abs(v.odometry - self.start_mm) >= covered_mm  # noqa: E731
        ctx.prims.wait_for(name, covered, '|odometry - start| >= %.1f mm' % covered_mm, timeout)

    def _stop(self, ctx):
        stop_wheels(ctx)
        if self.method == 'odometry':
            driven = ctx.feed.latest().odometry - self.start_mm
            error = abs(driven - ctx.goal.distance)
            if error > ctx.guards.drive['tolerance']:
                raise PabFailed('drove %.1f mm of %.1f mm (tolerance %.0f mm)'
                                % (driven, ctx.goal.distance, ctx.guards.drive['tolerance']))
            self.driven = driven

    def summary(self, ctx):
        if self.method == 'odometry':
            return 'drove %.1f mm by odometry (asked %.1f mm)' % (self.driven, ctx.goal.distance)
        return 'drove %.1f mm by time, eq 5.3 (no odometry)' % ctx.goal.distance
