"""Home (report 4.7.4.2.1, Fig 4.9): unclamp and lay the robot down.

As far as the report went: it assumes a robot clamped straight. Change
control modes, unclamp front, unclamp rear, move the front module down.
"""
from pirate.sequencer.pabs.base import ALWAYS, END, Pab, StateMachine, Transition

CHANGE_MODES = 'change control modes'
UNCLAMPING_FRONT = 'unclamping front'
UNCLAMPING_REAR = 'unclamping rear'
MOVING_FRONT_DOWN = 'moving front down'

MACHINE = StateMachine(CHANGE_MODES, (
    Transition(CHANGE_MODES, UNCLAMPING_FRONT, ALWAYS),
    Transition(UNCLAMPING_FRONT, UNCLAMPING_REAR, ALWAYS),
    Transition(UNCLAMPING_REAR, MOVING_FRONT_DOWN, ALWAYS),
    Transition(MOVING_FRONT_DOWN, END, ALWAYS),
))


class Home(Pab):
    """Unclamp front, then rear, then lower the front module."""

    name = 'Home'
    machine = MACHINE
    leaves = 'unclamped'

    def actions(self):
        return {
            CHANGE_MODES: self._change_modes,
            UNCLAMPING_FRONT: lambda ctx: ctx.prims.unclamp('front'),
            UNCLAMPING_REAR: lambda ctx: ctx.prims.unclamp('rear'),
            MOVING_FRONT_DOWN: lambda ctx: ctx.prims.move_front('move_front_down'),
        }

    @staticmethod
    def _change_modes(ctx):
        for bend in ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv'):
            ctx.prims.change_control_mode(bend, 'torque')
        ctx.prims.change_control_mode('front_tilt', 'pwm')

    def summary(self, ctx):
        return 'unclamped and lying in the pipe, %d motion primitives' % len(ctx.prims.executed)
