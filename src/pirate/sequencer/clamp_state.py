"""How clamped each part of the robot is, from what the robot senses.

The server's idle state (report Fig 4.2: Idle Clamped / Idle Unclamped)
must come from the robot, not from which PAB ran last: a cancel or an abort
can leave a part anywhere between free and clamped. PABs that need to know
where they start (issue 10) use the same classifier. Pure Python.

Per part (front = Bend I/II, rear = Bend IV/III, SPEC 2) the classes are:

- ``full``: both bends past the full clamp guard (Table 5.2);
- ``custom``: past a custom clamp guard (Table 5.3) but not the full one;
- ``free``: both bends back inside the full unclamp guard AND neither
  spring pushes in the clamping direction (effort, signed like the clamp
  setpoint of Table 5.2, below ``spring_contact_mnm``);
- ``partly clamped``: anything else - bends between open and clamped, or
  bends that look open while a spring says they press on something.

Why the spring only decides free vs partly: the worm gears (24:1) hold a
clamp after the motor is switched to PWM 0 (the safe hold), and the spring
then reads whatever the gear keeps, down to nothing; the angles past the
clamp guard are what say the V spans the pipe. An open-looking part with a
loaded spring is touching the wall or an obstacle and is not free. Only
the clamping direction counts: an unclamp drives the bends against their
straight stop, which loads the springs the other way.

The angle thresholds are the guard rows of ``config/guards_<mm>.yaml``;
the spring threshold is that file's ``clamp_state`` row, so each pipe
diameter carries its own numbers as data.
"""
import collections

FREE, PARTLY, CUSTOM, FULL = 'free', 'partly clamped', 'custom', 'full'
PARTS = ('front', 'rear')
#: Custom clamp rows per part, most specific last (Table 5.3).
CUSTOM_ROWS = {'front': ('clamp_front_custom_first', 'clamp_front_custom'),
               'rear': ('clamp_rear_custom',)}

IDLE_CLAMPED = 'Idle Clamped'
IDLE_UNCLAMPED = 'Idle Unclamped'
IDLE_PARTLY = 'Idle Partly Clamped'

#: The clamp state of the whole robot: one class per part.
ClampState = collections.namedtuple('ClampState', 'front rear')


def spring_contact_mnm(guards):
    """Spring effort (mNm, clamping direction) at which a bend presses on the wall."""
    return float(guards.row('clamp_state')['spring_contact_mnm'])


def classify_part(guards, part, angles, efforts):
    """Class of ``part`` ('front'/'rear') from joint ``angles`` (rad) and ``efforts`` (mNm)."""
    if guards.pair('clamp', part).closed(angles):
        return FULL
    for row in CUSTOM_ROWS[part]:
        if guards.has(row) and guards.pair(row, part).closed(angles):
            return CUSTOM
    if guards.pair('unclamp', part).opened(angles) and not pressing(guards, part, efforts):
        return FREE
    return PARTLY


def pressing(guards, part, efforts):
    """True when a bend of ``part`` pushes in its clamping direction (sign of its clamp setpoint)."""
    contact = spring_contact_mnm(guards)
    clamp = guards.pair('clamp', part)
    return any(efforts.get(bend.joint, 0.0) * (1 if bend.setpoint > 0 else -1) >= contact
               for bend in (clamp.outer, clamp.inner))


def classify(guards, angles, efforts):
    """:data:`ClampState` of both parts."""
    return ClampState(*(classify_part(guards, part, angles, efforts) for part in PARTS))


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
