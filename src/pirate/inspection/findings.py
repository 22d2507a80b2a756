"""What a finding is and where it was seen: pure, no ROS.

A finding is one JSON object (a line of the run's findings.jsonl,
pirate.inspection.store): its number, kind, note, times, its position on
the map (:func:`position_on_map`) and the file names of the camera frames
saved with it.

Positions are metres along the map's path (as in
pirate.supervisory.planner and localiser). The robot never turns round: its
front always faces away from the start of the path, so the front camera
looks the way the path's distance grows, out and back. Clock positions are
as seen looking that way: 12 at the top of the pipe, 3 on the right.
"""
import math

from pirate.supervisory import planner
from pirate.world import network

#: A frame taken to look, not a defect (an inspection stop's sweep): in the
#: report, not in the dig list.
VIEW = 'view'
#: What a finding may be: what the world format's defects are, other, or a view.
KINDS = tuple(network.DEFECT_KEYS) + ('other', VIEW)
#: The robot's roll when upright (Fig 4.7: pi/2 upright, 0 lying on its right side).
UPRIGHT_RAD = math.pi / 2
#: A camera within this angle of the pipe's axis sees the whole ring ahead: no clock position.
AHEAD_RAD = math.radians(5)


class FindingError(ValueError):
    """A finding that cannot be recorded: says why."""


def check_kind(kind):
    """The kind, lower case, or :class:`FindingError` naming the known ones."""
    name = (kind or 'other').strip().lower()
    if name not in KINDS:
        raise FindingError('kind %r is not one of %s' % (kind, ', '.join(KINDS)))
    return name


def clock_position(pan_rad, tilt_rad, roll_rad):
    """The wall's clock position (1.0 .. 12.99, 12 at the top) the front
    camera looks at, or None when it looks along the pipe (within
    :data:`AHEAD_RAD`).

    The camera's view in the front module's frame (x ahead, y left, z up):
    tilt about -y (positive looks up), then pan about z (positive looks
    left): (cos t cos p, sin p, sin t cos p). Its part across the pipe,
    turned by the robot's roll away from upright (a roll above pi/2 lies
    towards the left side, turning the view anticlockwise), gives the
    clock."""
    left, up = math.sin(pan_rad), math.sin(tilt_rad) * math.cos(pan_rad)
    if math.hypot(left, up) < math.sin(AHEAD_RAD):
        return None
    clockwise_from_top = math.atan2(-left, up) - (roll_rad - UPRIGHT_RAD)
    hours = (math.degrees(clockwise_from_top) / 30.0) % 12.0
    return 12.0 if round(hours, 1) in (0.0, 12.0) else hours


def clock_text(hours):
    """'10 o'clock', 'half past 2' ... or 'ahead' for None."""
    if hours is None:
        return 'ahead (camera along the pipe)'
    whole = int(round(hours * 2)) / 2.0
    whole = 12.0 if whole == 0 else whole
    hour = int(whole) if int(whole) else 12
    return ("%d o'clock" % hour) if whole == int(whole) else ('half past %d' % hour)


def segments(network):
    """[(name, start_m, end_m)] of the map's straight pipes in path order: pipe_1, pipe_2 ..."""
    found, along, count = [], 0.0, 0
    for piece in network.pieces:
        if piece.kind == 'straight':
            count += 1
            found.append(('pipe_%d' % count, along, along + piece.length))
        along += piece.length
    return found


def position_on_map(network, along_m, launch_m, uncertainty_m, pan_rad, tilt_rad, roll_rad):
    """Where a finding is: a dict of the distance from the launch pit along
    the route, the segment (straight pipe) and the distance from the
    junction before it on the path (or from the path's start), the
    clock position, and the uncertainty of the distance (m, the
    localiser's bound). ``along_m``: the robot's middle, m along the path."""
    if not 0.0 <= along_m <= network.length:
        raise FindingError('the robot at %.0f mm is off the map (0..%.0f mm)' % (along_m * 1000,
                                                                                 network.length * 1000))
    segment, start_m = 'junction', 0.0
    for name, start, end in segments(network):
        if start <= along_m <= end:
            segment, start_m = name, start
    before = [j for j in planner.junctions(network) if j.exit_m <= along_m + 1e-9]
    junction = before[-1].name if before else 'the start of the map'
    from_m = before[-1].exit_m if before else 0.0
    if segment == 'junction':
        inside = [j for j in planner.junctions(network) if j.entry_m <= along_m <= j.exit_m]
        segment = inside[0].name if inside else segment
    clock = clock_position(pan_rad, tilt_rad, roll_rad)
    return {'along_mm': round(along_m * 1000, 1), 'from_launch_pit_mm': round(abs(along_m - launch_m) * 1000, 1),
            'segment': segment, 'segment_start_mm': round(start_m * 1000, 1),
            'last_junction': junction, 'from_last_junction_mm': round((along_m - from_m) * 1000, 1),
            'clock': None if clock is None else round(clock, 2), 'clock_text': clock_text(clock),
            'uncertainty_mm': round(uncertainty_m * 1000, 1)}


def dig_list(findings):
    """The findings (views left out) sorted by their distance from the
    launch pit, each with its line 'dig at X m from the launch pit along the
    route'."""
    placed = sorted((f for f in findings if f.get('kind') != VIEW),
                    key=lambda f: (f['position']['from_launch_pit_mm'], f['number']))
    return [(f, 'dig at %.2f m (+/- %.2f m) from the launch pit along the route'
             % (f['position']['from_launch_pit_mm'] / 1000.0, f['position']['uncertainty_mm'] / 1000.0))
            for f in placed]
