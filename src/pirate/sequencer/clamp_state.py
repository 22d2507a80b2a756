"""How clamped each part of the robot is, from what the robot senses.

The server's idle state (report Fig 4.2: Idle Clamped / Idle Unclamped)
must come from the robot, not from which PAB ran last: a cancel or an abort
can leave a part anywhere between free and clamped. PABs that need to know
where they start use the same classifier. Pure Python.

Per part (front = Bend I/II, rear = Bend IV/III, SPEC 2) the classes are:

- ``full``: both bends past the full clamp guard (Table 5.2) AND the outer
  bend's spring presses toward the wall (effort, signed like the clamp
  setpoint of Table 5.2, at least ``spring_clamp_mnm``);
- ``custom``: the same with a custom clamp guard (Table 5.3) instead;
- lying on a side (the part's roll within the row's ``within_rad`` of 0
  or pi, else the nominal band, Fig 4.7; the rear's roll is the IMU's, the
  front's that less the rotation) the V spans the pipe's chord through its
  axis, not the diameter, and meets the walls short of the full guard: there ``full``
  uses the ``clamp_sideways`` row (derived from that chord, see
  config/guards_<mm>.yaml), so a Clamp Sideways reads as clamped and the
  server accepts Drive after it; a custom row with a ``_sideways`` twin
  uses that twin on a side the same way;
- ``free``: both bends back inside the full unclamp guard (give or take
  ``free_margin_rad``) AND neither spring pushes in the clamping direction
  (``spring_contact_mnm``);
- ``partly clamped``: anything else - bends between open and clamped, bends
  past a clamp guard with the V short of the wall (a cancel between the
  guard and the wall leaves that), or open-looking bends whose spring says
  they press on something.

Why angles AND spring (report 7.2 recommends combining both): the
guard angle alone called a part clamped 0.04-0.11 rad short of the wall.
Only the outer bend's spring says the V spans the pipe: the clamp releases
the inner bend (setpoint 0) once its guard holds, and while the V closes
the inner spring loads against the floor before the apex meets the wall
(twin, 90 mm, cancelled at the guard: inner -194 mNm, outer -34 mNm, no
wall contact; clamped: outer 241 mNm). The clamp threshold sits between
what a spring carries without the wall and the clamp's torque: bends held
by their worms carry the robot's weight at 100-130 mNm (twin), and a clamp
judged at 60 mNm was a false success (bench/pab_clamp_sweep: retried after
a cancel, "clamped" with the rear apex off the wall;
measurements.md#clamp-spring-thresholds). The worm gears keep the spring's
deflection when the motors stop, so a clamp held at PWM 0 still reads as
pressing. Only the clamping direction counts: an unclamp drives the bends
against their straight stop, which loads the springs the other way.

Why a margin on "clamped" (``clamp_margin_rad``): a clamp stops at its
guard and the V then settles back a few encoder counts as the worm takes
the load (twin, 90 mm MITRE_BEND RIGHT at 15 mm/s: the front's Bend I at
-0.600 rad when its clamp ended, -0.598 two seconds later, spring still
242 mNm on the wall; the server said "front partly clamped" after a
successful turn). The spring decides whether the V presses the wall: the
margin is far smaller than the 0.04-0.11 rad short of the wall a cancel
can leave, which the spring rules out anyway.

Why a margin on "free": Home's unclamp stops a part exactly at its unclamp
guard, and the part then settles a few hundredths of a rad as its held
inner bend takes up the outer bend's closure (seq_mission, 1 run in 6 under
load: bend III 0.0736 rad against the 0.07 guard, no spring pressing, and the
server said "rear partly clamped" right after Home said unclamped). The
primitive's guard stays exact; the classification has the hysteresis, so
the state the operator reads does not flip on a settling bend.

The angle thresholds are the guard rows of ``config/guards_<mm>.yaml``;
the spring threshold is that file's ``clamp_state`` row, so each pipe
diameter carries its own numbers as data.
"""
import collections
import math

FREE, PARTLY, CUSTOM, FULL = 'free', 'partly clamped', 'custom', 'full'
PARTS = ('front', 'rear')
#: Custom clamp rows per part, most specific last (Table 5.3).
CUSTOM_ROWS = {'front': ('clamp_front_custom_first', 'clamp_front_custom'),
               'rear': ('clamp_rear_custom',)}

IDLE_CLAMPED = 'Idle Clamped'
IDLE_UNCLAMPED = 'Idle Unclamped'
IDLE_PARTLY = 'Idle Partly Clamped'

#: Target orientations (rad, Fig 4.7) where the robot lies on a side.
SIDES_RAD = (0.0, math.pi)
#: Suffix of a guard row for the robot lying on a side (config/guards_<mm>.yaml).
SIDEWAYS = '_sideways'

#: The clamp state of the whole robot: one class per part.
ClampState = collections.namedtuple('ClampState', 'front rear')


def spring_contact_mnm(guards):
    """Spring effort (mNm, clamping direction) at which a bend touches something."""
    return float(guards.row('clamp_state')['spring_contact_mnm'])


def spring_clamp_mnm(guards):
    """Spring effort (mNm, clamping direction) of an outer bend clamping on the wall."""
    return float(guards.row('clamp_state')['spring_clamp_mnm'])


def free_margin_rad(guards):
    """How far (rad) past the unclamp guard a part with no spring pressing still reads as free."""
    return float(guards.row('clamp_state')['free_margin_rad'])


def clamp_margin_rad(guards):
    """How far (rad) short of a clamp guard a part whose outer spring presses the wall still reads as clamped."""
    return float(guards.row('clamp_state')['clamp_margin_rad'])


def on_side(guards, orientation, half=None):
    """True when the roll ``orientation`` (rad) lies within ``half`` rad of a
    side (default: the nominal band around it)."""
    if orientation is None:
        return False
    if half is None:
        low, high = guards.region('nominal')
        half = (high - low) / 2.0
    return any(abs(math.remainder(orientation - side, 2 * math.pi)) <= half for side in SIDES_RAD)


def part_roll(part, angles, orientation):
    """Roll (rad, Fig 4.7) of ``part`` ('front'/'rear') from what the robot
    senses: the rear's is the IMU's ``orientation``; the front's is the
    rear's less the rotation (Table 4.5: theta = rear roll - front roll).
    None when the orientation is unknown."""
    if orientation is None or part == 'rear':
        return orientation
    return orientation - angles.get('rotation', 0.0)


def row_at(guards, row, orientation=None):
    """Guard ``row`` for a robot at roll ``orientation`` (rad): ``<row>_sideways``
    when the diameter has that row and the robot lies on a side (within the
    row's own ``within_rad`` of it, or the nominal band), else ``row``."""
    sideways = row + SIDEWAYS
    if not guards.has(sideways):
        return row
    return sideways if on_side(guards, orientation, guards.row(sideways).get('within_rad')) else row


def full_row(guards, orientation=None):
    """The guard row of a full clamp at ``orientation`` (rad): ``clamp``, or ``clamp_sideways`` on a side."""
    return row_at(guards, 'clamp', orientation)


def classify_part(guards, part, angles, efforts, orientation=None):
    """Class of ``part`` ('front'/'rear') from joint ``angles`` (rad), ``efforts`` (mNm)
    and the rear's roll ``orientation`` (rad; None: upright guards). Each
    part is judged by the rows of its own roll (:func:`part_roll`): the
    rotation can put the front on a side while the rear is not."""
    roll, margin = part_roll(part, angles, orientation), clamp_margin_rad(guards)
    if clamped(guards, guards.pair(full_row(guards, roll), part), angles, efforts, margin):
        return FULL
    for row in CUSTOM_ROWS[part]:
        if guards.has(row) and clamped(guards, guards.pair(row_at(guards, row, roll), part), angles, efforts, margin):
            return CUSTOM
    if guards.pair('unclamp', part).opened(angles, free_margin_rad(guards)) and not pressing(guards, part, efforts):
        return FREE
    return PARTLY


def clamped(guards, pair, angles, efforts, margin_rad=0.0):
    """True when the clamp ``pair`` holds: its angle guards (less ``margin_rad``)
    AND its outer spring on the wall. Exact (no margin): the clamp primitive's
    guard; the classification passes ``clamp_margin_rad``, so a clamp that
    settles back past its guard while its spring presses the wall does not
    flip to "partly clamped"."""
    return pair.closed(angles, margin_rad) and presses_wall(guards, pair.outer, efforts)


def presses_wall(guards, bend, efforts):
    """True when ``bend``'s spring pushes in its clamping direction at least
    ``spring_clamp_mnm``: the V presses the wall whatever its angles."""
    return _pushes(bend, efforts, spring_clamp_mnm(guards))


def pressing(guards, part, efforts):
    """True when a bend of ``part`` pushes in its clamping direction (sign of its clamp setpoint)."""
    clamp = guards.pair('clamp', part)
    contact = spring_contact_mnm(guards)
    return any(_pushes(bend, efforts, contact) for bend in (clamp.outer, clamp.inner))


def _pushes(bend, efforts, threshold_mnm):
    sign = 1 if bend.setpoint > 0 else -1
    return (efforts or {}).get(bend.joint, 0.0) * sign >= threshold_mnm


def classify(guards, angles, efforts, orientation=None):
    """:data:`ClampState` of both parts."""
    return ClampState(*(classify_part(guards, part, angles, efforts, orientation) for part in PARTS))


def sensed(guards, view):
    """:data:`ClampState` of the robot in ``view`` (a :class:`pirate.state.feed.RobotView`)."""
    return classify(guards, view.angles, view.efforts, view.orientation)


def idle_state(clamp):
    """The server's idle state (Fig 4.2) for a :data:`ClampState`.

    Idle Clamped only when both parts are fully clamped (what Drive needs);
    Idle Unclamped only when both are free; otherwise "Idle Partly Clamped"
    naming each part, so the operator sees what a cancel left behind.
    """
    if clamp.front == FULL and clamp.rear == FULL:
        return IDLE_CLAMPED
    if clamp.front == FREE and clamp.rear == FREE:
        return IDLE_UNCLAMPED
    return '%s (front %s, rear %s)' % (IDLE_PARTLY, clamp.front, clamp.rear)
