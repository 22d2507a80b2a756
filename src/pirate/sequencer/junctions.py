"""Which clamp a junction needs before the robot takes it (report 4.7.4).

"Depending on the direction desired (left or right) and the orientation of
the bend itself, the clamping required beforehand could be straight or
sideways (left or right)." Two rules behind it:

- **steering**: the robot steers into a new pipe by bending its body, and
  it bends only in the plane of its V's (the bending plane, vertical when
  clamped straight, horizontal when clamped sideways). A turn left or right
  needs the bending plane horizontal: clamp sideways, lying toward the turn
  (LEFT: orientation pi, RIGHT: 0, Fig 4.7); a turn up or down needs it
  vertical: clamp straight;
- **sensing**: going straight through a T-joint the junction PAB senses the
  open side only with the front V's apex pressing toward it (its spring
  unloads where the wall goes away, pirate.sequencer.junction_sensing; in
  the twin: upright below a hole above, lying on a side next to a hole on
  that side; with the V facing away nothing is sensed and the goal ends
  junction_missing). So clamp with the apex toward the open side:
  straight (apex up) for a side open upward, sideways toward a side open
  left or right. No clamp of the PABs faces down (that would be upside
  down): a T-joint open downward cannot be gone straight through.

Directions are relative to the pipe before the junction, as the world
format (pirate.world.network) and the Pirate.action options give them.

The planner asks :func:`required_clamp`, and drives past a T-joint open to
a side clamped straight (:func:`driven_past`); whether the junction PAB starts
from that clamp is the PAB's own declaration (its ``JUNCTIONS`` table),
read by :func:`pirate.sequencer.goals.start_clamps`, so a route the PAB
cannot start is refused before the robot moves
(pirate.supervisory.planner.check_runnable). Pure, and imports no PAB.
"""
import collections

Clamp = collections.namedtuple('Clamp', 'pab side')

STRAIGHT_CLAMP = Clamp('CLAMP_STRAIGHT', None)
TURNS = ('left', 'right', 'up', 'down')
#: The clamp whose front V's apex faces each open side of a T-joint (sensing rule).
FACING_OPEN_SIDE = {'up': STRAIGHT_CLAMP, 'left': Clamp('CLAMP_SIDEWAYS', 'LEFT'),
                    'right': Clamp('CLAMP_SIDEWAYS', 'RIGHT')}


def required_clamp(kind, direction, open_side=None):
    """The :data:`Clamp` to hold before taking a junction.

    ``kind``: 'mitre' or 'tee'; ``direction``: one of :data:`TURNS` or
    'straight' (tee only); ``open_side``: the tee's open side when going
    straight through it. ValueError with the reason when none serves.
    """
    if direction in ('left', 'right'):
        return Clamp('CLAMP_SIDEWAYS', direction.upper())
    if direction in ('up', 'down'):
        return STRAIGHT_CLAMP
    if kind == 'tee' and direction == 'straight':
        if open_side not in FACING_OPEN_SIDE:
            raise ValueError('a T-joint open %s cannot be gone straight through: no clamp turns the front '
                             'V\'s apex toward it, so the junction PAB cannot sense it' % open_side)
        return FACING_OPEN_SIDE[open_side]
    raise ValueError('a %s cannot be taken %r' % (kind, direction))


#: Open sides of a T-joint gone straight through that the robot drives past
#: clamped straight instead of taking it with the junction PAB (:func:`driven_past`).
DRIVEN_PAST_OPEN = ('left', 'right')


def driven_past(kind, direction, open_side):
    """True for a T-joint gone straight through whose open side is left or
    right: clamped straight (upright) the V's wheels press the pipe's top
    and bottom, which a side branch of the same diameter leaves whole (it
    cuts the run's wall down to those two lines only), so a Drive crosses it
    and no part has to open. The junction PAB would have to lie on that side
    to sense the hole and cross it one part open at a time (taken where the
    diameter's guards have ``straight_sideways_speed_min``: 90 and 110 mm);
    the Drive is the simpler way. Nothing is sensed on the way, so no junction
    anchors the odometry there. Twin: bench/tee_drive_past. A
    tee open downward is not driven past: lying on a side the drive stalled
    over the hole (twin, 90 mm, both sides), and upright too: from start rolls
    70-110 deg, 6 of 9 Drives did not get past (4 stalled at 233 mm of
    odometry, the front wheels over the hole; 2 stood short at 508 mm); the
    3 that did were at 100 mm/s from within 10 deg of upright (none at 50
    mm/s), too narrow a band to plan on (twin, 90 mm, tee_run_down_90)."""
    return kind == 'tee' and direction == 'straight' and open_side in DRIVEN_PAST_OPEN


def is_turn(direction):
    """True when a junction taken in ``direction`` leaves for a new pipe
    (one of :data:`TURNS`), False straight on: the two ways a junction PAB
    senses and ends (the supervisory layer anchors and plans by it)."""
    return direction in TURNS


def label(clamp):
    """The junction PAB's name for ``clamp`` ('straight', 'sideways LEFT', ...)."""
    return 'straight' if clamp == STRAIGHT_CLAMP else 'sideways %s' % clamp.side
