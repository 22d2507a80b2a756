"""Route planner: from named points on a pipe map to the PAB goals that get there.

The Supervisory layer (report 3.2) thinks in routes ("from the launch pit,
to the T-joint, right, on to the target, and back"); the Pirate Server runs
PABs. :func:`plan` turns one into the other, before anything moves, so the
plan can be printed and checked (``rosrun pirate plan_mission MAP FROM TO``):

- clamp before each junction the way the junction needs
  (:func:`pirate.sequencer.junctions.required_clamp`), and once at the start;
- drive each segment by distance, stopping the leading end ``approach_mm``
  before the junction (drives longer than one Drive goal may go are split),
  at the mission's speed; every other PAB at its own (speed 0: a junction
  PAB searches and crosses at the speed it was measured at);
- take each mitre bend / T-joint in the direction the route goes; backwards
  (rear first: the rear part leads, the robot backs out the way it came) on
  the way back, which the goal says by a negative search distance; straight
  on past a T-joint open to the left or right, drive past it clamped
  straight instead (:func:`pirate.sequencer.junctions.driven_past`), either
  way;
- drive on to the target; home at the end.

Positions are metres along the map's path (pirate.world.network), of the
robot's middle. Every step says where it starts, where it should end and
which junction it should meet, which is what localisation checks against.
Pure: no ROS; the map, the settings (config/supervisory.yaml) and the
Drive limit (config/sequencer.yaml) are passed in; :func:`check_runnable`
reads the guard files once unless given them.
"""
import collections

from pirate.sequencer import goals
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.junctions import STRAIGHT_CLAMP, driven_past, is_turn, label, required_clamp
from pirate.sequencer.pabs.junction import not_taken_why
from pirate.world.network import turns_at_corner

#: One junction of the map, as the route meets it. ``from_run``: a T-joint
#: entered through its run and left by its branch.
Junction = collections.namedtuple('Junction', 'name kind direction open_side entry_m exit_m diameter_mm from_run',
                                  defaults=(False,))
#: One PAB goal of the plan. ``option``: None or LEFT/RIGHT/UP/DOWN/STRAIGHT;
#: ``distance_mm`` signed (Drive: how far; junction PABs: how far at most to
#: search, which the executive narrows to what the map allows);
#: ``junction``: the :data:`Junction` a junction PAB should meet (else None);
#: ``holds``: the clamp the robot holds when the step starts (None: none yet),
#: which a retry or a resume re-establishes first.
Step = collections.namedtuple('Step', 'pab option distance_mm speed_mm_s pipe_diameter start_m end_m '
                                      'junction note holds')
Plan = collections.namedtuple('Plan', 'map_name waypoints steps')


class PlanError(ValueError):
    """A route the map cannot serve, with the reason."""


def junctions(network):
    """The map's junctions in path order, named mitre_1, tee_1, ..."""
    found, along, count = [], 0.0, collections.Counter()
    for piece in network.pieces:
        if piece.kind in ('mitre', 'tee'):
            count[piece.kind] += 1
            direction, open_side, from_run = _crossing(piece)
            found.append(Junction('%s_%d' % (piece.kind, count[piece.kind]), piece.kind, direction, open_side,
                                  along, along + piece.length, round(piece.diameter * 1000), from_run))
        along += piece.length
    return found


def turns(junction):
    """True when a route takes ``junction`` into a new pipe (a bend, a T-joint's branch), False straight on."""
    return is_turn(junction.direction)


def _crossing(piece):
    """(direction taken, open side, from_run) of a junction on the path: the
    same both ways in the robot's own frame (it drives back without turning
    round). A tee the path turns at (entered through its branch, or through
    its run and left by its branch: from_run) is a turn to its side, the way
    it does not take straight on; through its run it is straight on, open to
    its side."""
    if piece.kind == 'mitre':
        return piece.spec['turn'], None, False
    if turns_at_corner(piece):
        return piece.spec['side'], 'straight', piece.spec['enter'] == 'run'
    return 'straight', piece.spec['side'], False


def plan(network, waypoints, settings, max_drive_mm, speed_mm_s=None, home=True):
    """A :data:`Plan` visiting ``waypoints`` (point names) in order."""
    if len(waypoints) < 2:
        raise PlanError('a route needs at least two points (from, to), got %r' % (waypoints,))
    places = [_place(network, name) for name in waypoints]
    planner = _Planner(network, settings, max_drive_mm, speed_mm_s or settings['speed_mm_s'])
    for (name_a, a), (name_b, b) in zip(zip(waypoints, places), zip(waypoints[1:], places[1:])):
        if abs(b - a) * 1000 < settings['min_drive_mm']:
            raise PlanError('%s and %s are the same place; nothing to drive' % (name_a, name_b))
        planner.leg(name_a, a, name_b, b)
    if home:
        planner.add('HOME', None, 0.0, planner.at, planner.at, None, 'unclamp at %s' % waypoints[-1])
    return Plan(network.name, list(waypoints), planner.steps)


def _place(network, name):
    if name not in network.points:
        raise PlanError('no point %r on map %s (points: %s)'
                        % (name, network.name, ', '.join(sorted(network.points)) or 'none'))
    along = network.points[name]
    kind = network.pieces[network.locate(along)[0]].kind
    if kind != 'straight':
        raise PlanError('point %s (%.0f mm) lies in a %s, not in a straight pipe' % (name, along * 1000, kind))
    return along


class _Planner(object):
    """Accumulates steps; knows where the robot is and how it is clamped."""

    def __init__(self, network, settings, max_drive_mm, speed):
        self.network, self.settings, self.speed = network, settings, speed
        self.max_drive_mm = max_drive_mm
        self.junctions = junctions(network)
        self.steps, self.clamp, self.at = [], None, None

    def add(self, pab, option, distance_mm, start_m, end_m, junction, note):
        diameter = round(self.network.diameter_at(start_m) * 1000)
        self.steps.append(Step(pab, option, distance_mm, self.speed if pab == 'DRIVE' else 0.0,
                               diameter, start_m, end_m, junction, note, self.clamp))

    def leg(self, name_a, a, name_b, b):
        """Steps from ``a`` to ``b`` (metres along), through the junctions between."""
        if self.at is None:
            self.at = a
        sign = 1 if b > a else -1
        crossed = [j for j in self.junctions if min(a, b) < j.entry_m and j.exit_m < max(a, b)]
        for junction in (crossed if sign > 0 else reversed(crossed)):
            if driven_past(junction.kind, junction.direction, junction.open_side):
                self._drive_past(junction, sign, b)
            else:
                self._take(junction, sign, name_a)
        if self.clamp is None:
            self._clamp(STRAIGHT_CLAMP, 'before driving to %s' % name_b)
        to_go_mm = (b - self.at) * 1000
        if to_go_mm * sign < -self.settings['min_drive_mm']:
            raise PlanError('%s (%.0f mm) lies before where %s leaves the robot (its middle at %.0f mm): the robot '
                            'ends past it' % (name_b, b * 1000, crossed[-1 if sign > 0 else 0].name, self.at * 1000))
        self._drive(to_go_mm, 'to %s' % name_b)

    def _take(self, junction, sign, came_from):
        self._check_takeable(junction)
        try:
            clamp = required_clamp(junction.kind, junction.direction, junction.open_side)
        except ValueError as why:
            raise PlanError('%s: %s' % (junction.name, why))
        self._clamp(clamp, 'for %s (%s %s)' % (junction.name, junction.kind, junction.direction))
        robot = self.settings['robot']
        lead_mm = robot['front_mm'] if sign > 0 else robot['rear_mm']
        edge_m = junction.entry_m if sign > 0 else junction.exit_m
        stop_m = edge_m - sign * (lead_mm + self.settings['approach_mm']) / 1000.0
        if (stop_m - self.at) * sign < -self.settings['min_drive_mm'] / 1000.0:
            raise PlanError('%s is too close to %s: the robot\'s %s end would already be within %.0f mm of it'
                            % (came_from, junction.name, 'front' if sign > 0 else 'rear',
                               self.settings['approach_mm']))
        self._drive((stop_m - self.at) * 1000, 'up to %s' % junction.name)
        clear_mm = self._turn_end_mm(junction, sign) if is_turn(junction.direction) else self.settings['clear_mm']
        after_m = (junction.exit_m if sign > 0 else junction.entry_m) + sign * clear_mm / 1000.0
        pab = 'MITRE_BEND' if junction.kind == 'mitre' else 'T_JOINT'
        self.add(pab, junction.direction.upper(), sign * self.settings['search_mm'], self.at, after_m,
                 junction, '%s %s%s' % (junction.name, junction.direction, '' if sign > 0 else ', rear first'))
        # The junction PAB ends clamped as it started: a turn lying on the same side (Clamp Sideways
        # straightens toward it), straight on through a T-joint upright (pirate.sequencer.pabs.junction).
        self.at, self.clamp = after_m, clamp

    def _drive_past(self, junction, sign, to_m):
        """Clamp straight, then drive until the trailing end is ``approach_mm``
        past ``junction`` (or to ``to_m``, the leg's end, if that comes first):
        a Drive, so no junction is met or anchored there."""
        self._clamp(STRAIGHT_CLAMP, 'to drive past %s (open %s)' % (junction.name, junction.open_side))
        robot = self.settings['robot']
        trail_mm = robot['rear_mm'] if sign > 0 else robot['front_mm']
        clear_m = (junction.exit_m if sign > 0 else junction.entry_m) + sign * (
            trail_mm + self.settings['approach_mm']) / 1000.0
        past_m = min(clear_m, to_m) if sign > 0 else max(clear_m, to_m)
        self._drive((past_m - self.at) * 1000, 'past %s (open %s: clamped straight, no wheel meets its opening)'
                    % (junction.name, junction.open_side))

    def _turn_end_mm(self, junction, sign=1):
        """How far past the junction a turn leaves the middle, mm: the robot's
        geometry round the corner, so one figure per pipe diameter (and, where
        it differs, for a T-joint entered through its run and left by its
        branch: ``turn_end_from_run_mm``); taken rear first (``sign`` -1),
        ``turn_end_rear_first_mm``, before the junction's entry."""
        key = 'turn_end_mm' if sign > 0 else 'turn_end_rear_first_mm'
        ends = self.settings.get(key) or {}
        from_run = self.settings.get('turn_end_from_run_mm') or {}
        if sign > 0 and junction.from_run and junction.diameter_mm in from_run:
            return from_run[junction.diameter_mm]
        if junction.diameter_mm not in ends:
            raise PlanError('%s: no turn end measured for a %d mm pipe (config/supervisory.yaml %s has %s)'
                            % (junction.name, junction.diameter_mm, key,
                               ', '.join(str(d) for d in sorted(ends)) or 'none'))
        return ends[junction.diameter_mm]

    def _check_takeable(self, junction):
        can = self.settings['takeable'].get(junction.diameter_mm, {}).get(junction.kind, [])
        if junction.direction not in can:
            raise PlanError('%s (%s, %s) cannot be taken in a %d mm pipe (takeable: %s)'
                            % (junction.name, junction.kind, junction.direction, junction.diameter_mm,
                               ', '.join(can) or 'nothing'))

    def _clamp(self, clamp, why):
        if clamp != self.clamp:
            self.add(clamp.pab, clamp.side, 0.0, self.at, self.at, None, 'clamp %s' % why)
            self.clamp = clamp

    def _drive(self, distance_mm, why):
        if abs(distance_mm) < self.settings['min_drive_mm']:
            return
        pieces = int(abs(distance_mm) // self.max_drive_mm) + 1
        for _ in range(pieces):
            part_mm = distance_mm / pieces
            self.add('DRIVE', None, part_mm, self.at, self.at + part_mm / 1000.0, None, 'drive %s' % why)
            self.at += part_mm / 1000.0


#: The first line of a printed plan: map, waypoints, PAB count.
PLAN_HEADER = 'plan on %s: %s (%d PABs)'
ROUTE_JOIN = ' -> '


def format_plan(route_plan):
    """The plan as lines for the operator, one per PAB goal."""
    lines = [PLAN_HEADER % (route_plan.map_name, ROUTE_JOIN.join(route_plan.waypoints), len(route_plan.steps))]
    for number, step in enumerate(route_plan.steps, 1):
        option = ' %s' % step.option if step.option else ''
        distance = ' %+.0f mm' % step.distance_mm if step.distance_mm else ''
        lines.append('%3d. %-15s%-9s%-10s %3d mm pipe  at %6.0f -> %6.0f mm   %s'
                     % (number, step.pab, option, distance, step.pipe_diameter,
                        step.start_m * 1000, step.end_m * 1000, step.note))
    return lines


def route_of(lines):
    """(map name, [waypoints]) from a plan :func:`format_plan` printed (a
    mission result's ``plan``, e.g. in a recording); None if it is not one."""
    header = lines[0] if lines else ''
    if not header.startswith('plan on ') or ': ' not in header:
        return None
    map_name, rest = header[len('plan on '):].rsplit(': ', 1)
    return map_name, rest.rsplit(' (', 1)[0].split(ROUTE_JOIN)


def check_runnable(route_plan, built=None, book=None):
    """Raise :class:`PlanError` naming the first step the Pirate Server cannot
    run (a PAB it does not have yet, an option its goal cannot carry, or a
    junction PAB that does not start from the clamp the route holds there, a
    junction taken rear first on the way back that the PAB does not take so),
    so that a mission through it is refused before the robot moves rather
    than stopped at that junction (a junction PAB that does not take that
    direction yet included). ``built(pab, option, rear_first=False)``: default
    pirate.sequencer.goals.built (asked with ``rear_first`` only for a step on the way back).
    ``book``: the guards each step's start clamp is checked against (default:
    config/guards_<mm>.yaml, read once here)."""
    built, book = built or goals.built, book or GuardBook(*load_files())
    for number, step in enumerate(route_plan.steps, 1):
        where = 'step %d (%s%s%s)' % (number, step.pab, ' %s' % step.option if step.option else '',
                                      ', %s' % step.junction.name if step.junction is not None else '')
        if step.option and step.option not in goals.PAB_OPTIONS.get(step.pab, ()):
            raise PlanError('%s: the Pirate Server\'s %s takes %s, not %s; the robot cannot take this route'
                            % (where, step.pab, ' / '.join(goals.PAB_OPTIONS.get(step.pab, ('no option',))),
                               step.option))
        if not built(step.pab, step.option or None):
            raise PlanError('%s: the Pirate Server cannot run %s%s yet; the robot cannot take this route'
                            % (where, step.pab, ' %s' % step.option if step.option else ''))
        if _rear_first(step) and not built(step.pab, step.option or None, rear_first=True):
            raise PlanError('%s: the Pirate Server cannot take %s %s rear first yet (%s); the robot cannot take '
                            'this route back through %s' % (where, step.pab, step.option,
                                                            not_taken_why(step.junction.kind,
                                                                          step.junction.direction, True),
                                                            step.junction.name))
        _check_start_clamp(where, step, book)


def _rear_first(step):
    """A junction step on the way back: searched backwards, the rear V leading."""
    return step.junction is not None and step.distance_mm < 0


def _check_start_clamp(where, step, book):
    """A junction step starts from the clamp the route holds there
    (:func:`required_clamp`); the junction PAB must declare it starts from it
    in the step's pipe (``book``: the guards of each diameter)."""
    if step.junction is None or step.holds is None:
        return
    guards = book.for_diameter(step.pipe_diameter) if step.pipe_diameter else None
    starts = goals.start_clamps(step.pab, step.option, guards)
    if label(step.holds) not in starts:
        raise PlanError('%s: the route holds clamp %s there (the front V facing %s), but %s %s starts from '
                        'clamp %s only; the robot cannot take this route yet'
                        % (where, label(step.holds), step.junction.open_side or 'the turn', step.pab,
                           step.option, ' or '.join(starts) or 'nothing'))
