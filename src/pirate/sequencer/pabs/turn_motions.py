"""The motions a junction PAB makes, each a few motion primitives with its
guard (report 4.7.4): drives by odometry, clamps by the robot's roll,
steering the front into the new pipe (levelling it, backing off an edge),
clamping at the corner, swinging the middle round and bringing the rear
through. :mod:`pirate.sequencer.pabs.junction` holds the table that orders
them; here is how each moves the robot and why, with the twin runs that
chose its numbers (the ``junction`` and ``turn`` rows of
``config/guards_<mm>.yaml``).
"""
import math

from pirate.robot import units
from pirate.sequencer import clamp_state
from pirate.sequencer.pabs.wheels import ROBOT_TRAVEL, STANDSTILL_MM_S, Progress, Travel, stop_wheels
from pirate.state.feed import TimedOut


def search_speed(goal, guards):
    """mm/s while looking and crossing (and a turn's drive into the new pipe):
    the goal's, else the junction row's."""
    return goal.speed or float(guards.row('junction')['search_speed'])


def turn_speed(goal, row):
    """mm/s while a turn steers the front in and swings the middle round: the
    goal's, else the turn row's ``steer_speed``. Pulling the rear through is at
    the row's ``pull_speed`` whatever the goal says (where the turn leaves the
    robot, config/supervisory.yaml turn_end_mm, was measured at it)."""
    return goal.speed or float(row['steer_speed'])


def slower(goal, row):
    """How many times longer than at ``steer_speed`` the speed-set phases may
    take: their time bounds (steer_base_s, steer_s_per_mm, timeout_s) were
    measured at ``steer_speed``; a slower goal stretches them by the ratio of
    the speeds, a faster one keeps them (never shortened)."""
    return max(1.0, float(row['steer_speed']) / turn_speed(goal, row))


def time_bound(ctx, distance, speed):
    """Robot seconds a drive of ``distance`` mm may take: ``time_factor`` times the
    time at the speed the wheel setpoint gives (whole counts per PICO sample),
    plus the drive's margin. A wheel that stops is caught sooner by the drive's
    no-progress check."""
    wheel_speed = units.wheel_speed_mm_s(speed)
    factor = float(ctx.guards.row('junction')['time_factor'])
    return factor * distance / wheel_speed + ctx.guards.drive['time_margin_s']


def drive_until(ctx, name, speed, guard, text, limit_s):
    """Drive at ``speed`` until ``guard`` (within ``limit_s`` robot s), then stop the wheels."""
    ctx.prims.drive_at_velocity(speed)
    try:
        ctx.prims.wait_for(name, guard, text, limit_s)
    finally:
        ctx.prims.drive_at_velocity(0.0)


def drive_by(ctx, name, distance, travel=ROBOT_TRAVEL, speed=None):
    """Drive ``distance`` mm of odometry (``travel``: which, wheels.Travel) at
    ``speed`` mm/s (default: the search speed), then stop."""
    speed = speed or search_speed(ctx.goal, ctx.guards)
    start = ctx.feed.latest()
    progress = Progress(ctx.guards.drive, start, travel)
    ctx.prims.drive_at_velocity(speed)
    ctx.prims.wait_for(name, lambda v: progress.check(v) and travel(v) - travel(start) >= distance,
                       'odometry +%.0f mm (%s)' % (distance, travel.text), time_bound(ctx, distance, speed))
    stop_wheels(ctx)


#: The part that stays clamped while the other crosses.
HOLDING = {'front': 'rear', 'rear': 'front'}


def drive_across(ctx, part):
    """Drive the junction row's ``cross_<part>_mm`` so ``part`` ('front' /
    'rear') crosses the junction straight on, by the odometry of the other
    part, clamped on the wall: the crossing part's V is open, and lying on
    a side that part rests on its shells while its three wheels spin free
    (twin: 251 mm of the robot's odometry for 96 mm travelled, rear over a
    T-joint's side hole). Lying on a side it drives at
    least the row's ``cross_speed_sideways``: the open front part on its
    shells, pushed at 25 mm/s, stalled at the hole (twin, 90 mm)."""
    row, view = ctx.guards.row('junction'), ctx.feed.latest()
    speed = search_speed(ctx.goal, ctx.guards)
    if lying_on_a_side(ctx.guards, view, part):
        speed = max(speed, float(row['cross_speed_sideways']))
    drive_by(ctx, 'drive %s across' % part, float(row['cross_%s_mm' % part]), Travel(HOLDING[part]), speed)


def lying_on_a_side(guards, view, part):
    """True when ``part``'s roll (its own, clamp_state.part_roll) is on a side."""
    return clamp_state.on_side(guards, clamp_state.part_roll(part, view.angles, view.orientation))


def open_to_cross(ctx, part):
    """Ready ``part`` ('front' / 'rear') to cross a T-joint straight on:
    open its V partly (held by the worms), so it does not press toward the
    open side. Lying on a side, the part pulled across (the rear) would rest
    on its shells, and the front V alone did not drag it (twin: stalled
    after 40 mm); clamped fully, its apex wheel dropped into the hole and
    caught the far edge. So there its outer bend presses lightly in torque
    (the junction row's ``cross_press_sideways_<part>``, counts; 0: open
    partly), the inner at 0: its wheels keep the walls and drive, and its
    apex gives way over the hole (twin, 90 mm)."""
    view = ctx.feed.latest()
    press = float(ctx.guards.row('junction')['cross_press_sideways_%s' % part])
    if not press or not lying_on_a_side(ctx.guards, view, part):
        ctx.prims.unclamp(part, partial=True)
        return
    pair = ctx.guards.pair(full_row_of(ctx.guards, view, part), part)
    torque(ctx.prims, **{pair.outer.joint: int(math.copysign(press, pair.outer.setpoint)), pair.inner.joint: 0})


def torque(prims, **counts):
    """Bends in torque mode at the given setpoints (counts)."""
    for joint, value in counts.items():
        prims.change_control_mode(joint, 'torque')
        prims.move_module(joint, value)


def full_row_of(guards, view, part):
    """The full clamp's guard row at ``part``'s own roll in ``view`` (upright
    or on a side; :func:`pirate.sequencer.clamp_state.part_roll`): the
    rotation can put the front on a side while the rear is not, and the
    clamp state the server reads afterwards judges each part by its own roll too."""
    return clamp_state.full_row(guards, clamp_state.part_roll(part, view.angles, view.orientation))


def clamp_full(ctx, part):
    """Clamp ``part`` with the full guards of its roll (upright or on a side)."""
    ctx.prims.clamp(part, full_row_of(ctx.guards, ctx.feed.latest(), part))


def press_what_is_clamped(ctx):
    """Each part whose outer spring presses the wall back in torque at its
    clamp setpoint, the inner bend at 0, as a clamp leaves it. A turn
    re-sent after a cancel finds its clamped parts held by their worms at
    PWM 0 (the safe hold); the steps it resumes pull against those clamps
    (twin: resumed without this, the middle did not swing round and the
    front did not pull the rear through, 60 s each). From a fresh start it
    sets what Clamp Sideways left."""
    guards, view = ctx.guards, ctx.feed.latest()
    for part in clamp_state.PARTS:
        pair = guards.pair(full_row_of(guards, view, part), part)
        if clamp_state.presses_wall(guards, pair.outer, view.efforts):
            torque(ctx.prims, **{pair.outer.joint: pair.outer.setpoint, pair.inner.joint: 0})


def level_front(ctx, target):
    """Rotate the front part, open while the rear is clamped, onto the roll
    ``target`` (rad) of the side the turn is taken on: rotation = rear roll -
    target (Table 4.5: the front's roll is the rear's less the rotation).
    Clamp Sideways ends with the rear within the straight band (+-0.05 rad)
    and the rotation within its tolerance (0.0425 rad), so the front part
    may lie 0.09 rad off the side; in the twin such a front (110 mm T-joint
    entered through its run, LEFT from 60 and 73 deg: rear 3.05 rad, rotation
    +0.036 to +0.044) kept to the wall away from the branch, rode past the
    opening and backing off did not help; levelled first, every approach
    roll turned in. Only where the turn row says ``level_front``: in 90 mm,
    where every approach roll turned in without it, levelling made the pull
    of the rear slip and the turn end 30 mm short in 2 of 3 probes."""
    view = ctx.feed.latest()
    ctx.prims.rotate(math.remainder(view.orientation - target, 2 * math.pi), 'level the front')


def tilt_along_the_turn(prims, row, view):
    """Front tilt PWM toward pi/2 - (Bend I + Bend II): the front module along the new pipe."""
    target = min(float(row['tilt_max_rad']), math.pi / 2 - view.angles['bend_i'] - view.angles['bend_ii'])
    limit = int(row['tilt_pwm_max'])
    pwm = int(float(row['tilt_gain']) * (target - view.angles['front_tilt']))
    prims.move_module('front_tilt', max(-limit, min(limit, pwm)))


def steered(row, view):
    """True when the front part has turned into the new pipe: Bend II round
    the corner, or (a row with ``steered_sum_rad``: a corner wide enough for
    Bend I to take part of the turn, the 110 mm T-joint) Bend I + Bend II,
    the front module's direction against the middle."""
    angles = view.angles
    return angles['bend_ii'] >= float(row['steered_rad']) or (
        'steered_sum_rad' in row and angles['bend_i'] + angles['bend_ii'] >= float(row['steered_sum_rad']))


def steered_text(row):
    text = 'bend_ii >= %.2f' % float(row['steered_rad'])
    if 'steered_sum_rad' in row:
        text += ' or bend_i + bend_ii >= %.2f' % float(row['steered_sum_rad'])
    return text


class Standing:
    """True once the wheels have stood (|velocity| under STANDSTILL_MM_S,
    encoders) ``seconds`` robot s on end."""

    def __init__(self, seconds):
        self.seconds, self.since = seconds, None

    def long(self, view):
        if abs(view.velocity) >= STANDSTILL_MM_S:
            self.since = None
            return False
        if self.since is None:
            self.since = view.stamp
        return view.stamp - self.since >= self.seconds


def left_s(ctx, end):
    """Robot s left until ``end``."""
    return max(end - ctx.feed.latest().stamp, 0.0)


def back_off(ctx, row, speed, end):
    """Drive back ``back_off_mm`` of odometry at ``speed``, the front tilt still
    along the turn. A back-off that stalls ends at its own time bound and the
    steering goes on; TimedOut only at ``end``, the steering's."""
    prims, back_mm = ctx.prims, float(row['back_off_mm'])
    at = ctx.feed.latest().odometry
    bound = min(time_bound(ctx, back_mm, speed), left_s(ctx, end))
    prims.drive_at_velocity(-speed)
    try:
        prims.follow('back off the edge', lambda v: tilt_along_the_turn(prims, row, v),
                     lambda v: v.odometry <= at - back_mm, 'odometry -%.0f mm' % back_mm, bound)
    except TimedOut:
        if left_s(ctx, end) <= 0.0:
            raise
    finally:
        prims.drive_at_velocity(0.0)


def backed_off_text(times):
    """What a result says of the edges the steering backed off ('' for none)."""
    return '; backed off an edge %d time%s' % (times, '' if times == 1 else 's') if times else ''


def clamp_at_corner(ctx):
    """The front V clamps in the new pipe with its inner bend (II) carrying the
    turn: the clamp's angle guard cannot hold there, so the guard is Bend I's
    spring pressing the wall with Bend II round the corner. Bend II is then
    released (0), as after a clamp, so the middle can swing."""
    row, guards = ctx.guards.row('turn'), ctx.guards
    pair = guards.pair(full_row_of(guards, ctx.feed.latest(), 'front'), 'front')
    torque(ctx.prims, **{pair.outer.joint: pair.outer.setpoint, pair.inner.joint: pair.inner.setpoint})
    inner = float(row['corner_inner_rad'])
    ctx.prims.wait_for('clamp front at the corner',
                       lambda v: (v.angles[pair.inner.joint] >= inner
                                  and clamp_state.presses_wall(guards, pair.outer, v.efforts)),
                       '%s >= %.2f and %s on the wall' % (pair.inner.joint, inner, pair.outer.joint))
    ctx.prims.move_module(pair.inner.joint, 0)


def swing_middle(ctx):
    """The rear, still clamped, drives the middle round the corner (Bend III
    compliant) until Bend III has taken the turn, at the turn's speed. Once Bend III says the
    middle has started round (``swing_open_rad``), Bend II pushes the front
    part's corner open (``swing_bend_ii`` counts, toward straight): the middle
    then follows the front into the new pipe whether or not a wall lies
    ahead of the corner. A mitre bend's far wall, or the run's far wall when
    a T-joint is entered through its branch, turns the middle by itself; a
    T-joint entered through its run has the run going on ahead instead, and
    there, with Bend II left compliant, the rear pushed the middle on into
    the run until the Bend II module caught on the branch's far edge, Bend
    III stuck at 0.96-0.99 rad (twin). Opening Bend II from the start of the
    swing wedged the middle in the 110 mm T-joint entered through its branch
    (Bend III 0.66-0.78 rad, where it otherwise breaks free): hence only
    once the middle has started round. bench/junction_turn_probe --pab
    T_JOINT --world tee_run_branch_left_90."""
    row, prims = ctx.guards.row('turn'), ctx.prims
    open_from, swung = float(row['swing_open_rad']), float(row['swing_rad'])
    opened = []

    def open_corner(view):
        if not opened and view.angles['bend_iii'] >= open_from:
            torque(prims, bend_ii=int(row['swing_bend_ii']))
            opened.append(view.stamp)
    torque(prims, bend_iii=0)
    prims.drive_at_velocity(turn_speed(ctx.goal, row))
    try:
        prims.follow('swing the middle', open_corner, lambda v: v.angles['bend_iii'] >= swung,
                     'bend_iii >= %.2f (Bend II opening from bend_iii >= %.2f)' % (swung, open_from),
                     float(row['timeout_s']) * slower(ctx.goal, row))
    finally:
        prims.drive_at_velocity(0.0)


def bring_rear(ctx):
    """The front, clamped in the new pipe, pulls the rear through: Bend III
    opening, Bend IV toward the turn side, until Bend III is past straight.
    Bend II is released again (0): held opening, it straightened the front
    part against the pull and the rear stayed at the corner (twin)."""
    row = ctx.guards.row('turn')
    counts = int(row['rear_bend_counts'])
    torque(ctx.prims, bend_ii=0, bend_iii=counts, bend_iv=-counts)
    through = float(row['rear_through_rad'])
    drive_until(ctx, 'bring the rear through', float(row['pull_speed']),
                lambda v: v.angles['bend_iii'] <= through, 'bend_iii <= %.2f' % through, float(row['timeout_s']))
