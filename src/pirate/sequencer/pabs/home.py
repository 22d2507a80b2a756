"""Home (report 4.7.4.2.1, Fig 4.9): unclamp and lay the robot down.

The report's steps (change control modes, unclamp front, unclamp rear,
move the front module down) from any pose: the wheels stopped first; a
front module lifted beyond a clamp's lift lowered to it first; a rotation
away from 0 aligned while the rear still holds; each unclamp waiting for
its open guard, so a part only partly clamped (or free) passes at once.
The front is lowered last only while it lies along the pipe: pointing
into an opening (a turn cancelled while steering in) it is left lifted and
the result says so. Half round a corner (:mod:`pirate.sequencer.pabs.half_round`)
Home is refused before anything moves: its unclamps open toward a
straight pipe's guards, which a part bent round the corner cannot reach;
re-sending the turn finishes it. Why each of these: doc/sequencer.md,
"Home".
"""
import collections

from pirate.sequencer.guards import CLAMP_BENDS
from pirate.sequencer.pabs import corner, half_round
from pirate.sequencer.pabs.base import ALWAYS, END, Pab, StateMachine, Transition
from pirate.sequencer.pabs.expr import fact, not_
from pirate.state.feed import TimedOut

CHANGE_MODES = 'change control modes'
LOWERING_FRONT = 'lowering the front'
UNCLAMPING_FRONT = 'unclamping front'
ALIGNING = 'aligning'
UNCLAMPING_REAR = 'unclamping rear'
MOVING_FRONT_DOWN = 'moving front down'
#: The guard row (config/guards_<mm>.yaml) of lowering a lifted front.
LOWER_ROW = 'move_front_home'
#: The guard row of Home's last step, the front down (config/sequencer.yaml).
DOWN_ROW = 'move_front_down'
#: The row of how far Bend I may bend with the front part along a straight pipe.
ALONG_ROW = 'home_front_down'

#: What Home's guards look at (each fact below says what its field is).
Facts = collections.namedtuple('Facts', 'aligned lifted along', defaults=(False, True))

ALIGNED = fact('aligned', means='|rotation| within the align tolerance')
LIFTED = fact('lifted', 'front lifted', "front tilt above the ``above`` of the diameter's ``move_front_home`` row")
#: Lowered after a turn that stopped steering into an opening, the front pried
#: the Bend I wheel on the wall with 16.9 N, the robot weighing 10.5 N, with
#: Bend I at -0.55 rad (twin, 90 mm mitre bend cancelled 19 s in).
ALONG = fact('along', 'front along the pipe', "Bend I at most the ``bend_i_max_rad`` of its ``home_front_down`` row, "
                                              'and the last goal not a turn that stopped steering the front into an '
                                              'opening where the robot still is')

T = Transition
MACHINE = StateMachine(CHANGE_MODES, (
    # state           next state         guard
    T(CHANGE_MODES,      UNCLAMPING_FRONT,  not_(LIFTED)),
    T(CHANGE_MODES,      LOWERING_FRONT,    LIFTED),
    T(LOWERING_FRONT,    UNCLAMPING_FRONT,  ALWAYS),
    T(UNCLAMPING_FRONT,  UNCLAMPING_REAR,   ALIGNED),
    T(UNCLAMPING_FRONT,  ALIGNING,          not_(ALIGNED)),
    T(ALIGNING,          UNCLAMPING_REAR,   ALWAYS),
    T(UNCLAMPING_REAR,   MOVING_FRONT_DOWN, ALONG),
    T(UNCLAMPING_REAR,   END,               not_(ALONG)),
    T(MOVING_FRONT_DOWN, END,               ALWAYS),
), facts=Facts)


class Home(Pab):
    """Lower a lifted front, unclamp front, align if needed, unclamp rear, lower the front module."""

    name = 'Home'
    machine = MACHINE

    def actions(self):
        return {
            CHANGE_MODES: self._change_modes,
            LOWERING_FRONT: lambda ctx: ctx.prims.move_front(LOWER_ROW),
            UNCLAMPING_FRONT: lambda ctx: self._unclamp(ctx, 'front'),
            ALIGNING: lambda ctx: ctx.prims.align(),
            UNCLAMPING_REAR: lambda ctx: self._unclamp(ctx, 'rear'),
            MOVING_FRONT_DOWN: lambda ctx: ctx.prims.move_front(DOWN_ROW),
        }

    def check(self, goal, view, guards):
        """Refused half round a corner (:func:`pirate.sequencer.pabs.half_round.said`):
        tried there, Home unclamped the front, stood 15 s against the walls,
        and left a robot neither the turn nor Home could go on from
        (bench/junction_turn_resume --then home --mm 110 [--pab T_JOINT])."""
        return half_round.refusal(guards, view, self.after, 'Home', "its unclamps open toward a straight pipe's "
                                  'guards, which a part bent round the corner cannot reach', then=', then Home')

    def facts(self, ctx):
        view = ctx.feed.latest()
        angles, steered = view.angles, half_round.stopped_steering(view, ctx.guards, self.after)
        return Facts(aligned=abs(angles['rotation']) <= ctx.guards.align_tolerance,
                     lifted=angles['front_tilt'] > float(ctx.guards.row(LOWER_ROW)['above']),
                     along=angles['bend_i'] <= _bend_i_max(ctx) and not steered)

    def _unclamp(self, ctx, part):
        """Open ``part``, then leave its outer bend compliant (torque 0) and
        hold its inner bend where it opened (PWM 0, the worm holds).

        Kept on, the unclamp torque drove the bends past straight into a
        reverse V that wedged the robot where it was (twin: on its side
        after a sideways clamp); both bends held at PWM 0 kept the robot's
        weight on the outer springs (100-130 mNm in the twin), which reads
        as pressing; an inner bend at torque 0 is closed again by the outer
        one (report Table 6.5's released inner bends).
        """
        try:
            ctx.prims.unclamp(part)
        except TimedOut as late:
            raise TimedOut('%s%s' % (late, _corner_hint(ctx, self.after))) from late
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
        count, view = len(ctx.prims.executed), ctx.feed.latest()
        angles = view.angles
        if angles['front_tilt'] <= ctx.guards.move(DOWN_ROW).guard:     # lowered (the ALONG path)
            return 'unclamped and lying in the pipe, %d motion primitives' % count
        return ('unclamped, the front module left lifted at %.2f rad and not lowered: %s; %d motion primitives'
                % (angles['front_tilt'], _why_left_lifted(ctx, view, self.after), count))


def _why_left_lifted(ctx, view, after):
    """What the robot senses that kept Home from lowering the front: the last
    goal stopped steering into an opening here, or Bend I past what a
    straight pipe allows (the bend reads the wall of a pipe it points into;
    whether there is a junction it cannot tell)."""
    if half_round.stopped_steering(view, ctx.guards, after):
        return 'the last goal, %s, stopped steering it into an opening here' % after.pab
    return ('Bend I senses %+.2f rad, past the %.2f rad a straight %d mm pipe allows: lowered, the front would be '
            'pressed against the wall Bend I leans on' % (view.angles['bend_i'], _bend_i_max(ctx),
                                                          ctx.guards.pipe_diameter))


def _corner_hint(ctx, after):
    """For an unclamp that did not open: where in a corner the robot senses it
    is, if anywhere short of the rear coming round, or that the last goal
    (``after``) stopped steering into an opening here ('' otherwise). With
    Bend III between the turn row's resume_middle_rad and swing_rad Home is
    only refused after a turn that stopped there (:meth:`Home.check`); from a
    manager restarted since, or the robot moved, it is tried. After a turn
    stopped steering in, Home is refused only with the front module down in
    the opening (``home_after_steering``); above it the unclamp may still
    block, and re-sending the turn is the way on (twin: every re-sent turn
    finished)."""
    view = ctx.feed.latest()
    sensed = corner.facts(ctx.guards, view)
    sensed.pop('trail_round', None)
    side = corner.side_turned(ctx.guards, view)
    if any(sensed.values()):
        said = 'the bends say half round a corner toward the %s (%s)' % (side, corner.text(view, sensed))
    elif half_round.stopped_steering(view, ctx.guards, after):
        said = ('the last goal, %s, stopped steering the front into an opening toward the %s here (front tilt '
                '%.2f rad)' % (after.pab, side, view.angles['front_tilt']))
    else:
        return ''
    return '; %s: if a turn was cancelled there, re-send it toward the %s to finish it, then Home' % (said, side)


def _bend_i_max(ctx):
    return float(ctx.guards.row(ALONG_ROW)['bend_i_max_rad'])
