"""Is the robot half round a corner? What the bends sense, and how the last goal ended.

A turn (pabs.junction) cancelled half round its corner leaves a robot that
only the turn re-sent can go on from: Home's unclamps open toward a straight
pipe's guards, which a part bent round the corner cannot reach, and a
Drive turns the wheels of the front part along the new pipe and of the rear
along the old one (twin: Home stood 15 s against the junction's walls and
aborted; a Drive stalled in 0.4 s). Both are refused there before anything
moves, naming what says so.

The bends alone do not tell the middle swinging round: a 110 mm Clamp
Sideways passes Bend III 0.95 rad in a straight pipe, a 110 mm T-joint
cancelled while swinging stood at 0.68 (twin). So the last goal counts
too (Pab.follows): a turn that stopped in its corner, bringing the rear
through with the middle still round, or steering with the front module
dropped into the opening, the robot not moved since.
"""
from pirate.sequencer.pabs import corner, junction_table

#: The guard row of the front tilt at which a turn's steer has put the front module in the opening.
STEERED_ROW = 'home_after_steering'


def said(guards, view, after):
    """What says the robot stands half round a corner, for a refusal ('' when nothing does).
    ``after``: how the last goal ended (:data:`~pirate.sequencer.pabs.base.Ended`, or None)."""
    sensed = corner.facts(guards, view)
    text = corner.text(view, {name: sensed.get(name) for name in ('lead_round', 'middle_swung')})
    steered_in = _steered_in(view, guards, after)
    if not (_stopped_in_a_corner(view, guards, after, sensed) or steered_in):
        return text
    return ', '.join(filter(None, (
        'the last goal, %s, stopped %s here' % (after.pab, after.state),
        text or corner.text(view, sensed),
        'front tilt %.2f rad: the front module dropped into the opening' % view.angles['front_tilt']
        if steered_in else '')))


def refusal(guards, view, after, pab, why, then=''):
    """Why ``pab`` cannot start half round a corner (``why``: what it would do
    there), naming what says so and the way out, the turn re-sent
    (``then``: what to send after it); None when nothing says so."""
    text = said(guards, view, after)
    if not text:
        return None
    side = corner.side_turned(guards, view)
    return ('%s cannot start half round a corner toward the %s (%s): %s; re-send the turn toward the %s to '
            'finish it%s' % (pab, side, text, why, side, then))


def stopped_steering(view, guards, after):
    """The last goal was a turn that stopped steering its front into the
    new pipe, and the robot has not moved since. Not one that ended for
    want of a junction: it steered along a straight pipe."""
    return (_stopped_here(view, guards, after) and after.state == junction_table.STEERING_FRONT
            and not after.junction_missing)


def _steered_in(view, guards, after):
    """The last goal stopped steering, the front module dropped into the
    opening (front tilt down to the diameter's ``entered_tilt_rad``)."""
    return (stopped_steering(view, guards, after)
            and view.angles['front_tilt'] <= float(guards.row(STEERED_ROW)['entered_tilt_rad']))


def _stopped_here(view, guards, after):
    """The last goal ended where the odometry still is (within the drive's tolerance, mm)."""
    return after is not None and abs(view.odometry - after.odometry_mm) <= float(guards.drive['tolerance'])


def _stopped_in_a_corner(view, guards, after, sensed):
    """The last goal was a turn that ended half round its corner (in one of
    its corner states, or bringing the rear through with the middle still
    round: ``sensed``, the corner facts, say Bend III is past the turn row's
    resume_middle_rad), and the robot has not moved since."""
    if not _stopped_here(view, guards, after):
        return False
    return after.state in junction_table.CORNER_STATES or (
        after.state in junction_table.BRINGING_STATES and sensed.get('middle_round'))
