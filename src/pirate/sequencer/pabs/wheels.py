"""Driving the wheels while clamped: what Drive and the turns share.

The speed a drive may be asked for (the wheels turn at whole counts per
PICO sample, and the progress watchdog needs a floor), the progress
watchdog itself (odometry must move while the wheels are commanded), and
stopping the wheels until the encoders say they stand.
"""
from pirate.robot import safety, units
from pirate.sequencer.pabs.base import PabFailed

STANDSTILL_MM_S = 1.0


def speed_problem(speed, slowest, settings):
    """Why a drive at ``speed`` mm/s (its slowest phase ``slowest``) cannot run, or
    None. The wheels turn at whole counts per PICO sample, and while they are
    commanded the odometry must gain ``no_progress_mm`` every ``no_progress_s``
    (:class:`Progress`): a speed that turns them slower than that would be
    accepted and then aborted by the watchdog while doing what it was asked."""
    if not safety.drive_speed_ok(speed) or speed <= 0:
        return 'drive speed %.1f mm/s outside (0, %.0f] mm/s' % (speed, safety.DRIVE_MAX_MM_S)
    turning = units.wheel_speed_mm_s(slowest)
    if turning == 0:
        return ('drive speed %.2f mm/s is below one wheel count per PICO sample (%.1f mm/s): '
                'the wheels would not turn' % (speed, units.wheel_counts_to_mm_s(1)))
    watched = settings['no_progress_mm'] / settings['no_progress_s']
    if turning < watched:
        return ('drive speed %.1f mm/s turns the wheels at %.1f mm/s (whole counts per PICO sample), '
                'slower than the progress watchdog needs: %.1f mm/s (config/sequencer.yaml drive '
                'no_progress_mm %.1f mm per no_progress_s %.1f s)'
                % (slowest, turning, watched, settings['no_progress_mm'], settings['no_progress_s']))
    return None


class Progress(object):
    """Odometry must move while the wheels are commanded, or the drive aborts.

    The first window is longer by ``no_progress_start_s``: the command takes
    a Mega cycle to reach the wheels and their motion one to come back
    (0.2 s) before the odometry can move, and at creep speed the default
    window left 2 mm of margin: under load in simulated time (x10) a -30 mm
    drive at 20 mm/s gained 1.8 mm in its first 0.4 s and aborted
    (seq_mission, a CI run)."""

    def __init__(self, settings, view, travel=None):
        self.window_s = settings['no_progress_s']
        self.min_mm = settings['no_progress_mm']
        self.travel = travel or ROBOT_TRAVEL
        self.mark_mm, self.mark_s = self.travel(view), view.stamp
        self.allowed_s = self.window_s + settings['no_progress_start_s']

    def check(self, view):
        """True to go on; PabFailed when the odometry stood still too long."""
        travelled = self.travel(view)
        if abs(travelled - self.mark_mm) >= self.min_mm:
            self.mark_mm, self.mark_s = travelled, view.stamp
            self.allowed_s = self.window_s
        elif view.stamp - self.mark_s > self.allowed_s:
            raise PabFailed('no odometry progress for %.1f s with the wheels commanded '
                            '(odometry %.1f mm, %s: boards silent, or the wheels stalled, '
                            'e.g. the robot against an end cap or an obstacle)'
                            % (view.stamp - self.mark_s, travelled, self.travel.text))
        return True


class Travel(object):
    """Which odometry a drive reads (mm from a RobotView): the robot's, or
    one part's own wheels (pirate.state.odometry)."""

    def __init__(self, part=None):
        self.part = part
        self.text = ("the median of the %s part's wheels" % part if part else 'the median of the drive boards')

    def __call__(self, view):
        return view.odometry if self.part is None else view.part_odometry[self.part]


ROBOT_TRAVEL = Travel()


def stop_wheels(ctx):
    """Wheels to 0, then wait until the encoders say they stand: the next
    step (the odometry's verdict, a clamp, sensing a junction's place) reads
    a robot at rest."""
    ctx.prims.drive_at_velocity(0.0)
    ctx.prims.wait_for('stop wheels', lambda v: abs(v.velocity) < STANDSTILL_MM_S,
                       '|velocity| < %.0f mm/s' % STANDSTILL_MM_S)
