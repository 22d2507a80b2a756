"""Clamp Straight and Clamp Sideways (report 4.7.4.1, 5.10, Table D.1; SPEC 8).

One machine and one class clamp the robot at a target orientation (Fig
4.7): upright (pi/2, Clamp Straight), lying on its left side (pi, Clamp
Sideways LEFT) or on its right side (0, Clamp Sideways RIGHT). The
"straight" and "nominal" regions of Table 5.4 are measured around the
target, and eqs 5.1 and 5.2 turn toward it; lying on a side a full clamp
is judged by the ``clamp_sideways`` guards and the outer spring on the
wall (:func:`pirate.sequencer.clamp_state.full_row`).

The transition table below is Table D.1 reconciled with the step lists the
report observed (Tables 6.1-6.3); where they differ, and why a rotate
rear clipped at the rotation limit does not count as done (the fact
``limited``): doc/sequencer.md, "Clamp Straight and Clamp Sideways".
Clamp states are remembered from the primitives that succeeded (the
start's from what the robot senses, :mod:`pirate.sequencer.clamp_state`).
"""
import collections
import math

from pirate.robot import safety
from pirate.sequencer import clamp_state
from pirate.sequencer.guards import CLAMP_BENDS
from pirate.sequencer.pabs import codes
from pirate.sequencer.pabs.base import ALWAYS, END, Pab, PabFailed, StateMachine, Transition
from pirate.sequencer.pabs.expr import all_of, any_of, equals, fact, named, not_

CHANGE_MODES = 'change control modes'
MOVING_FRONT = 'moving front'
CLAMPING_REAR = 'clamping rear'
CLAMPING_FRONT = 'clamping front'
UNCLAMPING_REAR = 'unclamping rear partial'
UNCLAMPING_FRONT = 'unclamping front partial'
ROTATING_REAR = 'rotating rear'
ROTATING_FRONT = 'rotating front'
CLAMPING_REAR_CUSTOM = 'clamping rear custom'
CLAMPING_FRONT_CUSTOM = 'clamping front custom'

NONE, CUSTOM, FULL = 'none', 'custom', 'full'

#: What the guards look at (each fact below says what its field is).
Facts = collections.namedtuple('Facts', 'nominal_start straight aligned front rear lift limited')

NOMINAL_START = fact('nominal_start', 'nominal start', "the roll at the start was in Table 5.4's nominal region")
STRAIGHT = fact('straight', means="the rear's roll in Table 5.4's straight region around the target")
ALIGNED = fact('aligned', means='the rotation within the align tolerance of 0: the front as straight as the rear')
LIMITED = fact('limited', means='the last rotate rear was clipped at the rotation limit')
#: front / rear: the part's clamp, NONE, CUSTOM (Table 5.3) or FULL, as the
#: primitives that succeeded left it (at the start: as the robot senses it).
FRONT_FREE = equals('front', NONE, 'front free', 'the front part is not clamped')
REAR_FREE = equals('rear', NONE, 'rear free', 'the rear part is not clamped')
FRONT_FULL = equals('front', FULL, means='the front part is clamped with the full guards')
REAR_FULL = equals('rear', FULL, means='the rear part is clamped with the full guards')
FRONT_CUSTOM = equals('front', CUSTOM, means='the front part is clamped with the custom guards')
REAR_CUSTOM = equals('rear', CUSTOM, means='the rear part is clamped with the custom guards')
FRONT_CLAMPED = named('front clamped', not_(FRONT_FREE), 'custom or full')
REAR_CLAMPED = named('rear clamped', not_(REAR_FREE), 'custom or full')
#: lift: 0 down, 1 first non-nominal lift, 2 lifted for a full front clamp.
FRONT_DOWN = equals('lift', 0, 'front down', 'the front module not lifted for this clamp yet')
FULLY_LIFTED = equals('lift', 2, 'front fully lifted', 'the front module lifted for a full front clamp')
FRONT_LIFTED = named('front lifted', not_(FRONT_DOWN), 'lifted once (non-nominal start) or fully')

DONE = named('done', all_of(FRONT_FULL, REAR_FULL, STRAIGHT, ALIGNED), 'clamped full, straight and aligned')
CUSTOM_NEEDED = named('custom needed', all_of(not_(NOMINAL_START), not_(STRAIGHT)),
                      "the custom clamps of Table 5.3: a non-nominal start, the rear not yet straight")

T = Transition
TRANSITIONS = (
    # state               next state             guard
    T(CHANGE_MODES,          END,                   DONE),
    T(CHANGE_MODES,          MOVING_FRONT,          all_of(not_(DONE), NOMINAL_START)),
    T(CHANGE_MODES,          CLAMPING_REAR_CUSTOM,  all_of(not_(DONE), not_(NOMINAL_START))),
    T(MOVING_FRONT,          CLAMPING_REAR,         not_(REAR_CLAMPED)),
    T(MOVING_FRONT,          CLAMPING_FRONT,        all_of(REAR_CLAMPED, not_(FRONT_CLAMPED), NOMINAL_START)),
    T(MOVING_FRONT,          CLAMPING_FRONT_CUSTOM, all_of(REAR_CLAMPED, not_(FRONT_CLAMPED), not_(NOMINAL_START))),
    T(MOVING_FRONT,          UNCLAMPING_REAR,       all_of(REAR_CLAMPED, FRONT_CLAMPED)),
    T(CLAMPING_REAR,         CLAMPING_FRONT,        not_(FRONT_CLAMPED)),
    T(CLAMPING_REAR,         UNCLAMPING_REAR,       all_of(FRONT_CLAMPED, not_(STRAIGHT), not_(LIMITED))),
    T(CLAMPING_REAR,         UNCLAMPING_FRONT,      all_of(FRONT_CLAMPED,
                                                           any_of(all_of(STRAIGHT, any_of(FRONT_CUSTOM, not_(ALIGNED))),
                                                                  all_of(not_(STRAIGHT), LIMITED)))),
    T(CLAMPING_REAR,         END,                   DONE),
    T(CLAMPING_FRONT,        CLAMPING_REAR,         not_(REAR_CLAMPED)),
    T(CLAMPING_FRONT,        UNCLAMPING_REAR,       all_of(REAR_CLAMPED, any_of(not_(STRAIGHT), REAR_CUSTOM))),
    T(CLAMPING_FRONT,        UNCLAMPING_FRONT,      all_of(REAR_FULL, STRAIGHT, not_(ALIGNED))),
    T(CLAMPING_FRONT,        END,                   DONE),
    T(UNCLAMPING_REAR,       ROTATING_REAR,         ALWAYS),
    T(ROTATING_REAR,         CLAMPING_REAR_CUSTOM,  CUSTOM_NEEDED),
    T(ROTATING_REAR,         CLAMPING_REAR,         not_(CUSTOM_NEEDED)),
    T(UNCLAMPING_FRONT,      ROTATING_FRONT,        ALWAYS),
    T(ROTATING_FRONT,        MOVING_FRONT,          not_(FRONT_LIFTED)),
    T(ROTATING_FRONT,        CLAMPING_FRONT_CUSTOM, all_of(FRONT_LIFTED, CUSTOM_NEEDED)),
    T(ROTATING_FRONT,        CLAMPING_FRONT,        all_of(FRONT_LIFTED, not_(CUSTOM_NEEDED))),
    T(CLAMPING_FRONT_CUSTOM, MOVING_FRONT,          not_(FULLY_LIFTED)),
    T(CLAMPING_FRONT_CUSTOM, UNCLAMPING_REAR,       FULLY_LIFTED),
    T(CLAMPING_REAR_CUSTOM,  ROTATING_FRONT,        not_(FRONT_CLAMPED)),
    T(CLAMPING_REAR_CUSTOM,  UNCLAMPING_FRONT,      FRONT_CLAMPED),
)

MACHINE = StateMachine(CHANGE_MODES, TRANSITIONS, facts=Facts)


#: What a sensed clamp class means to this table at the start: a part only
#: partly clamped (or short of the wall) has to be clamped again.
START_CLAMP = {clamp_state.FULL: FULL, clamp_state.CUSTOM: CUSTOM}


UPRIGHT = math.pi / 2
#: Target orientation (rad, Fig 4.7) per goal: CLAMP_STRAIGHT, and
#: CLAMP_SIDEWAYS by its option.
SIDES = {codes.LEFT: ('LEFT', math.pi), codes.RIGHT: ('RIGHT', 0.0)}


def target_of(goal):
    """Target orientation (rad) of a clamp goal, or None when it names no side."""
    if goal.name == codes.CLAMP_STRAIGHT:
        return UPRIGHT
    side = SIDES.get(goal.option)
    return side[1] if side else None


def in_region(orientation, region):
    """True when ``orientation`` (rad) lies in the (low, high) ``region``."""
    return region[0] <= orientation <= region[1]


def region_around(guards, name, target):
    """Region ``name`` of Table 5.4 (given around pi/2) moved to ``target`` (rad)."""
    low, high = guards.region(name)
    return low - UPRIGHT + target, high - UPRIGHT + target


def limit_rotation(rad):
    """Saturate a rotation target at the safety limit (report 5.10.1)."""
    top = safety.ROTATION_MAX_RAD
    return max(-top, min(top, rad))


class Clamp(Pab):
    """Clamp at ``target`` rad (upright or on a side) from any start the guards allow."""

    machine = MACHINE

    @classmethod
    def for_goal(cls, goal):
        return cls(target_of(goal))

    def __init__(self, target=UPRIGHT):
        self.target = target
        self.name = 'Clamp Straight' if target == UPRIGHT else 'Clamp Sideways'
        self.nominal_start = True
        self.clamp = {'front': NONE, 'rear': NONE}
        self.lift = 0
        self.front_custom_done = False
        self.limited = False
        self.off_band_rolls = []     # rad, where each full front clamp in a row left the robot off its band

    def check(self, goal, view, guards):
        if self.target is None:
            return ('CLAMP_SIDEWAYS needs a side: option LEFT (%d) or RIGHT (%d), not %r'
                    % (min(SIDES), max(SIDES), goal.option))
        return None

    def actions(self):
        return {
            CHANGE_MODES: self._change_modes,
            MOVING_FRONT: self._move_front,
            CLAMPING_REAR: lambda ctx: self._clamp(ctx, 'rear', self._full_row(ctx), FULL),
            CLAMPING_FRONT: self._clamp_front_full,
            CLAMPING_REAR_CUSTOM: lambda ctx: self._clamp_custom(ctx, 'rear', 'clamp_rear_custom'),
            CLAMPING_FRONT_CUSTOM: self._clamp_front_custom,
            UNCLAMPING_REAR: lambda ctx: self._unclamp(ctx, 'rear'),
            UNCLAMPING_FRONT: lambda ctx: self._unclamp(ctx, 'front'),
            ROTATING_REAR: self._rotate_rear,
            ROTATING_FRONT: self._rotate_front,
        }

    def facts(self, ctx):
        view = ctx.feed.latest()
        return Facts(nominal_start=self.nominal_start,
                     straight=in_region(view.orientation, region_around(ctx.guards, 'straight', self.target)),
                     aligned=abs(view.angles['rotation']) <= ctx.guards.align_tolerance,
                     front=self.clamp['front'], rear=self.clamp['rear'], lift=self.lift,
                     limited=self.limited)

    def _full_row(self, ctx):
        """Guards of a full clamp at the target: upright Table 5.2's, on a side
        the chord's (the V meets the walls short of -0.77 rad there,
        config/guards_<mm>.yaml ``clamp_sideways``); the same rule as the
        clamp state the server reads afterwards."""
        return clamp_state.full_row(ctx.guards, self.target)

    def _lift_row(self, ctx):
        """Guards of the nominal front lift at the target: on a side the front
        swings toward a wall, not up (``move_front_sideways``: lifted to
        0.4 rad in 90 mm it pushed the wall and rolled the twin 0.07 rad)."""
        return clamp_state.row_at(ctx.guards, 'move_front', self.target)

    # --- actions ----------------------------------------------------------
    def _change_modes(self, ctx):
        """Bends to torque, rotation to position (report 5.10), and read the start.

        A part that starts clamped keeps its bends' mode: after a cancel the
        worms hold it at PWM 0, and torque mode at setpoint 0 would let the
        clamp go (twin: the rear opened to -0.44 rad while the retried goal
        clamped the front, and the goal "succeeded"; bench/pab_clamp_sweep).
        """
        view = ctx.feed.latest()
        self.nominal_start = in_region(view.orientation, region_around(ctx.guards, 'nominal', self.target))
        sensed = clamp_state.sensed(ctx.guards, view)._asdict()
        for part in ('front', 'rear'):
            self.clamp[part] = START_CLAMP.get(sensed[part], NONE)
            if self.clamp[part] == NONE:
                for bend in CLAMP_BENDS[part]:
                    ctx.prims.change_control_mode(bend, 'torque')
        self.lift = self._lift_sensed(ctx, view.angles['front_tilt'])
        ctx.prims.change_control_mode('rotation', 'position')
        ctx.prims.change_control_mode('front_tilt', 'pwm')

    def _lift_sensed(self, ctx, tilt):
        """Lift stage (``lift`` fact) the front tilt (rad) already stands at.

        The stages are those this start's sequence lifts through: the
        nominal lift of the target, or the two non-nominal lifts (Table
        5.3). A front left at the sideways lift (0.16 rad) counted as fully
        lifted for a non-nominal start, so its later custom clamps ran with
        the front short of move_front_later, and there the twin's front V
        pressed the wall short of the guard (90 mm, RIGHT from 180 deg,
        front lifted: Bend I -0.680 rad against -0.72, front tilt 0.17).
        """
        if self.nominal_start:
            stages = ((2, self._lift_row(ctx)),)
        else:
            stages = ((2, 'move_front_later'), (1, 'move_front_first'))
        return next((stage for stage, row in stages if tilt >= ctx.guards.move(row).guard), 0)

    def _move_front(self, ctx):
        if self.nominal_start:
            ctx.prims.move_front(self._lift_row(ctx))
            self.lift = 2
        elif self.lift == 0:
            ctx.prims.move_front('move_front_first')
            self.lift = 1
        else:
            ctx.prims.move_front('move_front_later')
            self.lift = 2

    def _clamp(self, ctx, part, kind, result):
        ctx.prims.clamp(part, kind)
        self.clamp[part] = result

    def _clamp_front_full(self, ctx):
        self._clamp(ctx, 'front', self._full_row(ctx), FULL)
        self._watch_re_adjust(ctx)

    def _watch_re_adjust(self, ctx):
        """Abort a re-adjust that repeats itself instead of converging.

        Each full front clamp that leaves the robot off the straight band
        starts another pass; when ``re_adjust: same_roll_passes`` of them in
        a row leave it at the same roll (within ``same_roll_rad``,
        config/sequencer.yaml), the next pass will too. In the twin a robot
        twisted when the rotation encoder was zeroed did that until the
        60-state cap (100 s): the front never lies where the encoder says,
        so its clamp pulls the rear off the band every time.
        """
        view, band = ctx.feed.latest(), region_around(ctx.guards, 'straight', self.target)
        if in_region(view.orientation, band):
            self.off_band_rolls = []
            return
        self.off_band_rolls.append(view.orientation)
        settings = ctx.guards.re_adjust
        passes = int(settings['same_roll_passes'])
        last = self.off_band_rolls[-passes:]
        if len(last) == passes and max(last) - min(last) <= settings['same_roll_rad']:
            raise PabFailed('%s does not converge: %d full front clamps in a row left the robot at %.3f to %.3f '
                            'rad, outside the straight band %.3f to %.3f rad; the front part does not lie where the '
                            'rotation encoder says (was the robot twisted when it was switched on? the encoder '
                            'is zeroed at start-up)' % ((self.name, len(last), min(last), max(last)) + band))

    def _clamp_front_custom(self, ctx):
        kind = 'clamp_front_custom' if self.front_custom_done else 'clamp_front_custom_first'
        self._clamp_custom(ctx, 'front', kind)
        self.front_custom_done = True

    def _clamp_custom(self, ctx, part, kind):
        """A custom clamp (Table 5.3) with the guards of the part's own roll.

        The report measured its front custom clamps with the front 0.7 rad
        off a side (Clamp Straight's eq 5.1 saturates there); Clamp Sideways
        turns the front onto the side itself, where its V meets the walls
        at the chord (twin, 90 mm, LEFT from 150 deg: front roll 3.133 rad,
        Bend I -0.638 rad with its spring at 240 mNm, short of -0.69), so a
        ``<kind>_sideways`` row (derived from the chord) takes over there.
        """
        view = ctx.feed.latest()
        roll = clamp_state.part_roll(part, view.angles, view.orientation)
        self._clamp(ctx, part, clamp_state.row_at(ctx.guards, kind, roll), CUSTOM)

    def _unclamp(self, ctx, part):
        """Partial unclamp before the part turns: toward a side (Clamp Sideways)
        the V must open past the chord it meets lying there, or it jams on
        the walls as the rotation brings it down (``unclamp_partial_sideways``)."""
        ctx.prims.unclamp(part, partial=True, row=clamp_state.row_at(ctx.guards, 'unclamp_partial', self.target))
        self.clamp[part] = NONE

    def _rotate_rear(self, ctx):
        """Eq 5.2 as an increment: turn the free rear part to the target."""
        view = ctx.feed.latest()
        target = view.angles['rotation'] + (self.target - view.orientation)
        self.limited = limit_rotation(target) != target
        ctx.prims.rotate(limit_rotation(target), name='rotate rear')

    def _rotate_front(self, ctx):
        """Eq 5.1: turn the free front part to the target, or align if the rear is there."""
        view = ctx.feed.latest()
        self.limited = False
        if in_region(view.orientation, region_around(ctx.guards, 'straight', self.target)):
            ctx.prims.rotate(0.0, name='rotate front (align)')
        else:
            ctx.prims.rotate(limit_rotation(view.orientation - self.target), name='rotate front')

    def summary(self, ctx):
        view = ctx.feed.latest()
        return ('clamped at %.3f rad (target %.3f rad), rotation %.3f rad, %d motion primitives'
                % (view.orientation, self.target, view.angles['rotation'], len(ctx.prims.executed)))
