"""Where in a corner the robot senses it stands (a turn of report 4.7.4, read back).

A turn leaves its signature in the bend angles; the front leading: Bend II
round (the front part turned into the new pipe), Bend III round (the middle
swinging round), Bend IV round (the rear V coming round); the rear leading,
the mirror: Bend III, Bend II, Bend I. The junction PAB resumes a
cancelled turn from them; Home refuses to start on them. Thresholds (rad):
the diameter's ``turn`` guard row; a diameter without one has no corner.
"""
from pirate.sequencer import clamp_state
from pirate.sequencer.pabs import turn_motions as motions
from pirate.sequencer.pabs.clamp import SIDES, in_region, region_around

BEND_NAMES = {'bend_i': 'Bend I', 'bend_ii': 'Bend II', 'bend_iii': 'Bend III', 'bend_iv': 'Bend IV'}


def facts(guards, view, lead=None):
    """The corner facts of junction.Facts, ``lead`` (turn_motions.Lead, default
    the front) leading: lead_round, corner_opening, middle_round,
    middle_swung, trail_round ({} without a ``turn`` row)."""
    if not guards.has('turn'):
        return {}
    lead = lead or motions.FRONT_LEADS
    row, angles = motions.turn_row(guards, lead), view.angles
    lead_round = motions.steered(row, view, lead)
    return dict(lead_round=lead_round,
                corner_opening=lead_round and opened_at_the_corner(guards, view, row, lead),
                middle_round=angles[lead.trail_inner] >= float(row['resume_middle_rad']),
                middle_swung=angles[lead.trail_inner] >= float(row['swing_rad']),
                trail_round=angles[lead.trail_outer] >= float(row['resume_rear_rad']))


def opened_at_the_corner(guards, view, row, lead):
    """The leading V, round the corner, clamped there with the middle
    swinging (the fact corner_opening): its outer bend pressing the wall,
    its inner opened below the corner clamp's ``corner_inner_rad``. The middle's swing opens the inner
    that way before the middle bend says so (twin, 90 mm mitre cancelled
    while swinging: Bend II 1.47-1.53 rad with Bend III 0.77-0.83, below
    ``resume_middle_rad``); a corner clamp closes the inner past its guard
    before its outer presses (Bend II 1.73-1.75 with Bend I's spring at
    -5..+127 mNm). measurements.md#turn-resume."""
    pair = motions.full_pair(guards, view, lead.part)
    return (view.angles[lead.inner] < float(row['corner_inner_rad'])
            and clamp_state.presses_wall(guards, pair.outer, view.efforts))


def text(view, facts, lead=None):
    """What says the robot is round a corner ('' when nothing does), for a refusal."""
    lead = lead or motions.FRONT_LEADS
    angles, said = view.angles, []
    if facts.get('lead_round'):
        said.append('%s %.2f rad: the %s turned into the new pipe' % (BEND_NAMES[lead.inner], angles[lead.inner],
                                                                      lead.part))
    if facts.get('middle_round') or facts.get('middle_swung'):
        said.append('%s %.2f rad: the middle swinging round' % (BEND_NAMES[lead.trail_inner],
                                                                angles[lead.trail_inner]))
    if facts.get('trail_round'):
        said.append('%s %+.2f rad: the %s V coming round' % (BEND_NAMES[lead.trail_outer],
                                                             angles[lead.trail_outer], lead.trail))
    return ', '.join(said)


def side_turned(guards, view):
    """LEFT / RIGHT: the side (Fig 4.7) whose nominal band holds the roll; clamped
    sideways toward a turn the robot lies on it. 'unknown side' otherwise."""
    for side, target in sorted(SIDES.values()):
        if in_region(view.orientation, region_around(guards, 'nominal', target)):
            return side
    return 'unknown side'
