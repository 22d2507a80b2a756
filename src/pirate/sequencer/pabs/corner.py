"""Where in a corner the robot senses it stands (a turn of report 4.7.4, read back).

A turn leaves its signature in the bend angles: Bend II round (the front
part turned into the new pipe), Bend III round (the middle swinging round),
Bend IV round (the rear V coming round). The junction PAB resumes a
cancelled turn from them; Home refuses to start on them. Thresholds (rad):
the diameter's ``turn`` guard row; a diameter without one has no corner.
"""
from pirate.sequencer.pabs import turn_motions as motions
from pirate.sequencer.pabs.clamp import SIDES, in_region, region_around


def facts(guards, view):
    """The corner facts of junction.Facts: front_round, middle_round, middle_swung, rear_round
    ({} without a ``turn`` row)."""
    if not guards.has('turn'):
        return {}
    row, angles = guards.row('turn'), view.angles
    return dict(front_round=motions.steered(row, view),
                middle_round=angles['bend_iii'] >= float(row['resume_middle_rad']),
                middle_swung=angles['bend_iii'] >= float(row['swing_rad']),
                rear_round=angles['bend_iv'] >= float(row['resume_rear_rad']))


def text(view, facts):
    """What says the robot is round a corner ('' when nothing does), for a refusal."""
    angles, said = view.angles, []
    if facts.get('front_round'):
        said.append('Bend II %.2f rad: the front turned into the new pipe' % angles['bend_ii'])
    if facts.get('middle_round') or facts.get('middle_swung'):
        said.append('Bend III %.2f rad: the middle swinging round' % angles['bend_iii'])
    if facts.get('rear_round'):
        said.append('Bend IV %+.2f rad: the rear V coming round' % angles['bend_iv'])
    return ', '.join(said)


def side_turned(guards, view):
    """LEFT / RIGHT: the side (Fig 4.7) whose nominal band holds the roll; clamped
    sideways toward a turn the robot lies on it. 'unknown side' otherwise."""
    for side, target in sorted(SIDES.values()):
        if in_region(view.orientation, region_around(guards, 'nominal', target)):
            return side
    return 'unknown side'
