"""Which clamp a junction needs before the robot takes it (report 4.7.4).

"Depending on the direction desired (left or right) and the orientation of
the bend itself, the clamping required beforehand could be straight or
sideways (left or right)." The rule behind it: the robot steers into a new
pipe by bending its body, and it bends only in the plane of its V's (the
bending plane, vertical when clamped straight, horizontal when clamped
sideways). So

- a turn left or right needs the bending plane horizontal: clamp sideways,
  lying toward the turn (LEFT: orientation pi, RIGHT: 0, Fig 4.7);
- a turn up or down needs it vertical: clamp straight;
- going straight through a T-joint, the V's must not press toward the open
  side (there is no wall there): straight when the open side is left or
  right, sideways when it is up or down.

Directions are relative to the pipe before the junction, as the world
format (pirate.world.network) and the Pirate.action options give them.
Pure; the planner and the junction PABs share it.
"""
import collections

Clamp = collections.namedtuple('Clamp', 'pab side')

STRAIGHT_CLAMP = Clamp('CLAMP_STRAIGHT', None)
TURNS = ('left', 'right', 'up', 'down')


def required_clamp(kind, direction, open_side=None):
    """The :data:`Clamp` to hold before taking a junction.

    ``kind``: 'mitre' or 'tee'; ``direction``: one of :data:`TURNS` or
    'straight' (tee only); ``open_side``: the tee's open side when going
    straight through it.
    """
    if direction in ('left', 'right'):
        return Clamp('CLAMP_SIDEWAYS', direction.upper())
    if direction in ('up', 'down'):
        return STRAIGHT_CLAMP
    if kind == 'tee' and direction == 'straight':
        return Clamp('CLAMP_SIDEWAYS', 'LEFT') if open_side in ('up', 'down') else STRAIGHT_CLAMP
    raise ValueError('a %s cannot be taken %r' % (kind, direction))
