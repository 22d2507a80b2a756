"""The motions a junction PAB makes, each a few motion primitives with its
guard (report 4.7.4): drives by odometry, clamps by the robot's roll,
steering the leading part into the new pipe (levelling it, backing off an
edge), clamping at the corner, swinging the middle round and bringing the
trailing part through. Each is written for either part leading
(:class:`Lead`): the front, driving forwards, or the rear, driving
backwards; the robot's two V's mirror each other about the middle (Bends I
/ II of the front, IV / III of the rear, the same signs when clamped), so
a motion uses the leading V's bends where the front-first one uses the
front's, and the wheels turn the other way. :mod:`pirate.sequencer.pabs.junction` holds the table that orders
them; here is how each moves the robot and why, with the twin runs that
chose its numbers (the ``junction`` and ``turn`` rows of
``config/guards_<mm>.yaml``).
"""
import collections
import math

from pirate.robot import units
from pirate.sequencer import clamp_state
from pirate.sequencer.guards import CLAMP_BENDS
from pirate.sequencer.pabs.wheels import ROBOT_TRAVEL, STANDSTILL_MM_S, Progress, Travel, stop_wheels
from pirate.state.feed import TimedOut


#: The part that stays clamped while the other crosses.
HOLDING = {'front': 'rear', 'rear': 'front'}


class Lead(collections.namedtuple('Lead', 'part trail sign')):
    """Which part leads through the junction: ``part`` ('front' / 'rear'),
    ``trail`` the other, ``sign`` of the wheels' travel (+1 forwards, -1
    backwards)."""

    __slots__ = ()

    @classmethod
    def of(cls, part):
        return cls(part, HOLDING[part], 1 if part == 'front' else -1)

    @property
    def outer(self):
        """The leading V's outer bend (Bend I / Bend IV)."""
        return CLAMP_BENDS[self.part][0]

    @property
    def inner(self):
        """The leading V's inner bend (Bend II / Bend III): the one round the corner first."""
        return CLAMP_BENDS[self.part][1]

    @property
    def trail_outer(self):
        return CLAMP_BENDS[self.trail][0]

    @property
    def trail_inner(self):
        """The trailing V's inner bend: the middle swinging round."""
        return CLAMP_BENDS[self.trail][1]

    def along(self, view, start, travel=None):
        """mm travelled the way this part leads since ``start`` (views; ``travel``: which odometry)."""
        travel = travel or ROBOT_TRAVEL
        return self.sign * (travel(view) - travel(start))


#: The front leading: forwards, as into the network.
FRONT_LEADS = Lead.of('front')

#: The key of the ``turn`` row whose entries stand for the row's own when the rear leads.
REAR_FIRST_KEY = 'rear_first'
#: The front module's lift before a turn taken rear first pulls it round the corner.
TRAIL_LIFT = 'move_front_trail'


def turn_row(guards, lead=None):
    """The diameter's ``turn`` row with ``lead`` (default the front) leading:
    the row itself when the front leads; when the rear leads, its
    ``rear_first`` entries over it (the same keys, read by the V's role:
    ``steer_bend_i`` / ``steer_bend_ii`` the leading V's outer / inner bend,
    ``rear_bend_counts`` and ``rear_through_rad`` the trailing part's pull),
    measured rear first in the twin."""
    row = guards.row('turn')
    if lead is None or lead.part == 'front' or not row.get(REAR_FIRST_KEY):
        return row
    merged = dict(row)
    merged.update(row[REAR_FIRST_KEY])
    return merged


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
    """Drive at ``speed`` (mm/s, signed) until ``guard`` (within ``limit_s`` robot s), then stop the wheels."""
    ctx.prims.drive_at_velocity(speed)
    try:
        ctx.prims.wait_for(name, guard, text, limit_s)
    finally:
        ctx.prims.drive_at_velocity(0.0)


def drive_by(ctx, name, distance, travel=ROBOT_TRAVEL, speed=None, lead=None):
    """Drive ``distance`` mm of odometry (``travel``: which, wheels.Travel) at
    ``speed`` mm/s (default: the search speed) the way ``lead`` leads
    (default the front: forwards), then stop."""
    lead = lead or FRONT_LEADS
    speed = speed or search_speed(ctx.goal, ctx.guards)
    start = ctx.feed.latest()
    progress = Progress(ctx.guards.drive, start, travel)
    ctx.prims.drive_at_velocity(lead.sign * speed)
    ctx.prims.wait_for(name, lambda v: progress.check(v) and lead.along(v, start, travel) >= distance,
                       'odometry %+.0f mm (%s)' % (lead.sign * distance, travel.text),
                       time_bound(ctx, distance, speed))
    stop_wheels(ctx)


def drive_across(ctx, part, lead=None):
    """Drive so ``part`` ('front' / 'rear') crosses the junction straight on,
    ``lead`` (:class:`Lead`, default the front) leading: the junction row's
    ``cross_front_mm`` for the leading part, ``cross_rear_mm`` for the
    trailing one (the V's mirror each other), by the odometry of the other
    part, clamped on the wall: the crossing part's V is open, and lying on
    a side that part rests on its shells while its three wheels spin free
    (twin: 251 mm of the robot's odometry for 96 mm travelled, rear over a
    T-joint's side hole). Lying on a side it drives at
    least the row's ``cross_speed_sideways``: the open front part on its
    shells, pushed at 25 mm/s, stalled at the hole (twin, 90 mm)."""
    lead = lead or FRONT_LEADS
    row, view = ctx.guards.row('junction'), ctx.feed.latest()
    speed = search_speed(ctx.goal, ctx.guards)
    if lying_on_a_side(ctx.guards, view, part):
        speed = max(speed, float(row['cross_speed_sideways']))
    role = 'front' if part == lead.part else 'rear'
    drive_by(ctx, 'drive %s across' % part, float(row['cross_%s_mm' % role]), Travel(HOLDING[part]), speed, lead)


def lying_on_a_side(guards, view, part):
    """True when ``part``'s roll (its own, clamp_state.part_roll) is on a side."""
    return clamp_state.on_side(guards, clamp_state.part_roll(part, view.angles, view.orientation))


def open_to_cross(ctx, part, lead=None):
    """Ready ``part`` ('front' / 'rear') to cross a T-joint straight on:
    open its V partly (held by the worms), so it does not press toward the
    open side. Lying on a side, the part pulled across (the rear) would rest
    on its shells, and the front V alone did not drag it (twin: stalled
    after 40 mm); clamped fully, its apex wheel dropped into the hole and
    caught the far edge. So there its outer bend presses lightly in torque
    (the junction row's ``cross_press_sideways_<part>``, counts; 0: open
    partly), the inner at 0: its wheels keep the walls and drive, and its
    apex gives way over the hole (twin, 90 mm). Its press is the row's for
    the part crossing first (``_front``: the leading one) or second."""
    lead = lead or FRONT_LEADS
    view = ctx.feed.latest()
    role = 'front' if part == lead.part else 'rear'
    press = float(ctx.guards.row('junction')['cross_press_sideways_%s' % role])
    if not press or not lying_on_a_side(ctx.guards, view, part):
        ctx.prims.unclamp(part, partial=True)
        return
    pair = full_pair(ctx.guards, view, part)
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


def full_pair(guards, view, part):
    """The outer and inner bends of ``part``'s full clamp (:func:`full_row_of`)."""
    return guards.pair(full_row_of(guards, view, part), part)


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
        pair = full_pair(guards, view, part)
        if clamp_state.presses_wall(guards, pair.outer, view.efforts):
            torque(ctx.prims, **{pair.outer.joint: pair.outer.setpoint, pair.inner.joint: 0})


def level_front(ctx, target, lead=None):
    """Rotate the leading part, open while the other is clamped, onto the roll
    ``target`` (rad) of the side the turn is taken on (Table 4.5: the front's
    roll is the rear's less the rotation; the rear's is the IMU's). The front
    leading: rotation = rear roll - target. The rear leading: rotation =
    target - front roll, the front's roll being the rear's less the rotation now.
    Clamp Sideways ends with the rear within the straight band (+-0.05 rad)
    and the rotation within its tolerance (0.0425 rad), so the front part
    may lie 0.09 rad off the side; in the twin such a front (110 mm T-joint
    entered through its run, LEFT from 60 and 73 deg: rear 3.05 rad, rotation
    +0.036 to +0.044) kept to the wall away from the branch, rode past the
    opening and backing off did not help; levelled first, every approach
    roll turned in. Only where the turn row says ``level_front``: in 90 mm,
    where every approach roll turned in without it, levelling made the pull
    of the rear slip and the turn end 30 mm short in 2 of 3 probes."""
    lead = lead or FRONT_LEADS
    view = ctx.feed.latest()
    if lead.part == 'front':
        turn_to = view.orientation - target
    else:
        turn_to = target - clamp_state.part_roll('front', view.angles, view.orientation)
    ctx.prims.rotate(math.remainder(turn_to, 2 * math.pi), 'level the %s' % lead.part)


def tilt_along_the_turn(prims, row, view):
    """Front tilt PWM toward pi/2 - (Bend I + Bend II): the front module along the new pipe."""
    target = min(float(row['tilt_max_rad']), math.pi / 2 - view.angles['bend_i'] - view.angles['bend_ii'])
    limit = int(row['tilt_pwm_max'])
    pwm = int(float(row['tilt_gain']) * (target - view.angles['front_tilt']))
    prims.move_module('front_tilt', max(-limit, min(limit, pwm)))


def steer_tilt(prims, row, lead):
    """What keeps the leading module along the new pipe while it steers: the
    front tilt (:func:`tilt_along_the_turn`) when the front leads; the rear
    module has no tilt, so nothing when the rear does."""
    if lead.part == 'front':
        return lambda v: tilt_along_the_turn(prims, row, v)
    return lambda v: None


def steered(row, view, lead=None):
    """True when the leading part (default the front) has turned into the new
    pipe: its V's inner bend (Bend II / Bend III) round the corner, or (a row
    with ``steered_sum_rad``: a corner wide enough for the outer bend to take
    part of the turn, the 110 mm T-joint) outer + inner, the leading module's
    direction against the middle."""
    lead, angles = lead or FRONT_LEADS, view.angles
    return angles[lead.inner] >= float(row['steered_rad']) or (
        'steered_sum_rad' in row and angles[lead.outer] + angles[lead.inner] >= float(row['steered_sum_rad']))


def steered_text(row, lead=None):
    lead = lead or FRONT_LEADS
    text = '%s >= %.2f' % (lead.inner, float(row['steered_rad']))
    if 'steered_sum_rad' in row:
        text += ' or %s + %s >= %.2f' % (lead.outer, lead.inner, float(row['steered_sum_rad']))
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


def back_off(ctx, row, speed, end, lead=None):
    """Drive back ``back_off_mm`` of odometry at ``speed`` (against the way
    ``lead`` leads), the front tilt still along the turn where the front
    leads. A back-off that stalls ends at its own time bound and the
    steering goes on; TimedOut only at ``end``, the steering's."""
    lead = lead or FRONT_LEADS
    prims, back_mm = ctx.prims, float(row['back_off_mm'])
    start = ctx.feed.latest()
    bound = min(time_bound(ctx, back_mm, speed), left_s(ctx, end))
    prims.drive_at_velocity(-lead.sign * speed)
    try:
        prims.follow('back off the edge', steer_tilt(prims, row, lead),
                     lambda v: lead.along(v, start) <= -back_mm, 'odometry %+.0f mm' % (-lead.sign * back_mm),
                     bound)
    except TimedOut:
        if left_s(ctx, end) <= 0.0:
            raise
    finally:
        prims.drive_at_velocity(0.0)


def backed_off_text(times):
    """What a result says of the edges the steering backed off ('' for none)."""
    return '; backed off an edge %d time%s' % (times, '' if times == 1 else 's') if times else ''


def clamp_at_corner(ctx, lead=None):
    """The leading V (default the front) clamps in the new pipe with its inner
    bend (II / III) carrying the turn: the clamp's angle guard cannot hold
    there, so the guard is its outer bend's spring pressing the wall with the
    inner round the corner. The inner is then released (0), as after a
    clamp, so the middle can swing."""
    lead = lead or FRONT_LEADS
    row, guards = turn_row(ctx.guards, lead), ctx.guards
    pair = full_pair(guards, ctx.feed.latest(), lead.part)
    torque(ctx.prims, **{pair.outer.joint: pair.outer.setpoint, pair.inner.joint: pair.inner.setpoint})
    inner = float(row['corner_inner_rad'])
    ctx.prims.wait_for('clamp %s at the corner' % lead.part,
                       lambda v: (v.angles[pair.inner.joint] >= inner
                                  and clamp_state.presses_wall(guards, pair.outer, v.efforts)),
                       '%s >= %.2f and %s on the wall' % (pair.inner.joint, inner, pair.outer.joint),
                       stood=lambda view: corner_stood(view, pair, lead))
    ctx.prims.move_module(pair.inner.joint, 0)


def corner_stood(view, pair, lead):
    """What a corner clamp read: its inner bend, its outer's spring and the
    middle (the trailing V's inner bend), which a re-sent turn decides from."""
    spring = (view.efforts or {}).get(pair.outer.joint, float('nan'))
    return "%s stood at %+.2f rad, %s's spring at %+.0f mNm, %s at %+.2f rad" % (
        pair.inner.joint, view.angles[pair.inner.joint], pair.outer.joint, spring, lead.trail_inner,
        view.angles[lead.trail_inner])


def swing_middle(ctx, lead=None):
    """The trailing part, still clamped, drives the middle round the corner
    (the trailing V's inner bend, Bend III when the front leads, compliant)
    until that bend has taken the turn, at the turn's speed. Once it says the
    middle has started round (``swing_open_rad``), the leading V's inner bend
    (Bend II when the front leads) pushes the leading part's corner open
    (``swing_bend_ii`` counts, toward straight): the middle
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
    lead = lead or FRONT_LEADS
    row, prims = turn_row(ctx.guards, lead), ctx.prims
    open_from, swung = float(row['swing_open_rad']), float(row['swing_rad'])
    middle, corner = lead.trail_inner, lead.inner
    opened = []

    def open_corner(view):
        if not opened and view.angles[middle] >= open_from:
            torque(prims, **{corner: int(row['swing_bend_ii'])})
            opened.append(view.stamp)
    torque(prims, **{middle: 0})
    prims.drive_at_velocity(lead.sign * turn_speed(ctx.goal, row))
    try:
        prims.follow('swing the middle', open_corner, lambda v: v.angles[middle] >= swung,
                     '%s >= %.2f (%s opening from %s >= %.2f)' % (middle, swung, corner, middle, open_from),
                     float(row['timeout_s']) * slower(ctx.goal, row))
    finally:
        prims.drive_at_velocity(0.0)


def bring_trail(ctx, lead=None):
    """The leading part, clamped in the new pipe, pulls the trailing one
    through, the leading V's inner bend released (0: held opening, it
    straightened the front part against the pull and the rear stayed at the
    corner, twin). The front leading: Bend III opening, Bend IV toward the
    turn side (``rear_bend_counts``), until Bend III is past straight
    (``rear_through_rad``). The rear leading, the row's ``rear_first``
    entries: the front V held toward its clamp (``rear_bend_counts`` -60)
    and through once Bend I, which came round the corner (at least
    ``resume_rear_rad``), is back past straight (at most
    ``rear_through_rad``): the front part lies in the new pipe (twin: the
    front V bent round the corner at Bend I +1.17 while Bend II stood at -0.36
    and never passed -0.6; held toward its clamp, the whole front part came
    into the new pipe, Bend I -0.56, Bend II +0.35). Pulled through, the
    front module is lifted first (``move_front_trail``): at a side's lift
    (0.16) its nose caught the bend's wall."""
    lead = lead or FRONT_LEADS
    row, prims = turn_row(ctx.guards, lead), ctx.prims
    if lead.trail == 'front':
        prims.move_front(TRAIL_LIFT)
    counts = int(row['rear_bend_counts'])
    torque(prims, **{lead.inner: 0, lead.trail_inner: counts, lead.trail_outer: -counts})
    through = float(row['rear_through_rad'])
    if row.get('through_bend', 'inner') == 'inner':
        bend = lead.trail_inner
        done, text = (lambda v: v.angles[bend] <= through), '%s <= %.2f' % (bend, through)
    else:
        bend, came_round = lead.trail_outer, float(row['resume_rear_rad'])
        seen = []

        def done(view):
            if view.angles[bend] >= came_round:
                seen.append(view.stamp)
            return bool(seen) and view.angles[bend] <= through
        text = '%s >= %.2f (round the corner), then <= %.2f' % (bend, came_round, through)
    drive_until(ctx, 'bring the %s through' % lead.trail, lead.sign * float(row['pull_speed']), done, text,
                float(row['timeout_s']))
