"""Home (report 4.7.4.2.1, Fig 4.9): unclamp and lay the robot down.

The report's Home assumes a robot clamped straight and aligned: change
control modes, unclamp front, unclamp rear, move the front module down.
A rotation left away from 0 (a cancel, a rotation at its limit) is
aligned while the rear still holds the robot (the free front part turns,
Table 4.5): otherwise the next Clamp Straight starts with the rotation at
its limit and loops there (issue 10). An aligned robot runs the report's
steps unchanged. The wheels are stopped first: Home starts from any pose,
a cancelled Drive included. Each unclamp waits for its open guard, so a
part that was only partly clamped (or free) passes at once.
"""
import collections

from pirate.sequencer.guards import CLAMP_BENDS
from pirate.sequencer.pabs.base import ALWAYS, END, Guard, Pab, StateMachine, Transition

CHANGE_MODES = 'change control modes'
UNCLAMPING_FRONT = 'unclamping front'
ALIGNING = 'aligning'
UNCLAMPING_REAR = 'unclamping rear'
MOVING_FRONT_DOWN = 'moving front down'

#: What Home's guards look at: aligned = |rotation| within the align tolerance.
Facts = collections.namedtuple('Facts', 'aligned')

ALIGNED = Guard('aligned', lambda f: f.aligned)
NOT_ALIGNED = Guard('NOT aligned', lambda f: not f.aligned)

MACHINE = StateMachine(CHANGE_MODES, (
    Transition(CHANGE_MODES, UNCLAMPING_FRONT, ALWAYS),
    Transition(UNCLAMPING_FRONT, UNCLAMPING_REAR, ALIGNED),
    Transition(UNCLAMPING_FRONT, ALIGNING, NOT_ALIGNED),
    Transition(ALIGNING, UNCLAMPING_REAR, ALWAYS),
    Transition(UNCLAMPING_REAR, MOVING_FRONT_DOWN, ALWAYS),
    Transition(MOVING_FRONT_DOWN, END, ALWAYS),
))


class Home(Pab):
    """Unclamp front, align if needed, unclamp rear, lower the front module."""

    name = 'Home'
    machine = MACHINE

    def actions(self):
        return {
            CHANGE_MODES: self._change_modes,
            UNCLAMPING_FRONT: lambda ctx: self._unclamp(ctx, 'front'),
            ALIGNING: lambda ctx: ctx.prims.align(),
            UNCLAMPING_REAR: lambda ctx: self._unclamp(ctx, 'rear'),
            MOVING_FRONT_DOWN: lambda ctx: ctx.prims.move_front('move_front_down'),
        }

    def facts(self, ctx):
        return Facts(aligned=abs(ctx.feed.latest().angles['rotation']) <= ctx.guards.align_tolerance)

    @staticmethod
    def _unclamp(ctx, part):
        """Open ``part``, then leave its outer bend compliant (torque 0) and
        hold its inner bend where it opened (PWM 0, the worm holds).

        Kept on, the unclamp torque drove the bends past straight into a
        reverse V that wedged the robot where it was (twin: on its side
        after a sideways clamp); both bends held at PWM 0 kept the robot's
        weight on the outer springs (100-130 mNm in the twin), which reads
        as pressing; an inner bend at torque 0 is closed again by the outer
        one (report Table 6.5's released inner bends).
        """
        ctx.prims.unclamp(part)
        outer, inner = CLAMP_BENDS[part]
        ctx.prims.move_module(outer, 0)
        ctx.prims.hold(inner)

    @staticmethod
    def _change_modes(ctx):
        ctx.prims.drive_at_velocity(0.0)
        for bend in ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv'):
            ctx.prims.change_control_mode(bend, 'torque')
        ctx.prims.change_control_mode('front_tilt', 'pwm')

    def summary(self, ctx):
        return 'unclamped and lying in the pipe, %d motion primitives' % len(ctx.prims.executed)
