"""Take T-joint and Take mitre bend (report 4.7.4): what each state does.

The report: "start clamped, then detect when the front part loses
traction, unclamp and rotate according to the desired direction and
reclamp the front part. This process has to be repeated so that the rear
part ... pass[es] the bend in the same fashion". One class serves both
junction kinds and every direction; what differs is data: :data:`JUNCTIONS`
(the clamps a goal starts from, :mod:`pirate.sequencer.junctions`' rules),
:data:`TAKEN` (what is built) and the diameter's ``junction`` and ``turn``
guard rows (config/guards_<mm>.yaml).

Either part leads: the front (driving forwards, into the network) or,
for a goal whose search distance is negative, the rear (driving backwards,
the way the robot came): :attr:`TakeJunction.lead` picks the table built for
it and the bends its motions read.

The transition table: :mod:`pirate.sequencer.pabs.junction_table`; the
motions of a turn: :mod:`pirate.sequencer.pabs.turn_motions`; the sensing
straight on: :mod:`pirate.sequencer.junction_sensing`. The whole story,
state by state: doc/sequencer.md.
"""
import collections
import math

from pirate.sequencer import clamp_state
from pirate.sequencer.junction_sensing import JunctionSensor
from pirate.sequencer.junctions import TURNS
from pirate.sequencer.pabs import codes
from pirate.sequencer.pabs import corner as corner_sensing
from pirate.sequencer.pabs import turn_motions as motions
from pirate.sequencer.pabs.base import Pab, PabFailed
from pirate.sequencer.pabs.clamp import Clamp, in_region, region_around
from pirate.sequencer.pabs import junction_table as table
from pirate.sequencer.pabs.junction_table import (  # noqa: F401  (the front-first states, by name)
    BRINGING_REAR, CHANGE_MODES, CLAMPING_FRONT, CLAMPING_AT_CORNER, CLAMPING_REAR, CROSSING_FRONT,
    CROSSING_REAR, DRIVING_IN, LIFTING_FRONT, MACHINE, MACHINES, RE_ADJUSTING, SEARCHING, STEERING_FRONT, STOPPING,
    STRAIGHTENING, SWINGING_MIDDLE, UNCLAMPING_FRONT, UNCLAMPING_REAR, Facts, first_step)
from pirate.sequencer.pabs.junction_table import SENSED_STATES  # noqa: F401  (the PAB's: where a localiser anchors)
from pirate.sequencer.pabs.wheels import Progress, speed_problem, stop_wheels
from pirate.state.feed import TimedOut

#: What a turn that did not succeed leaves once its trailing part came round
#: the corner, for the same goal re-sent (the server keeps it,
#: :meth:`TakeJunction.unfinished`): the fact it makes true (``trail_through``,
#: ``driving_in``, ``driven_in``) while the odometry lies in ``from_mm`` ..
#: ``to_mm`` (give or take the drive's tolerance): where the trailing part came
#: through; the drive in from its start to its planned end; once driven,
#: to where the wheels stopped. ``lead``: the part that led ('front' / 'rear'),
#: so a turn taken the other way is not resumed from it.
PastCorner = collections.namedtuple('PastCorner', 'fact from_mm to_mm lead', defaults=('front',))

UPRIGHT = math.pi / 2
#: Clamp orientations (rad, Fig 4.7) by name.
ORIENTATIONS = {'straight': UPRIGHT, 'sideways LEFT': math.pi, 'sideways RIGHT': 0.0}
#: Where the front V's apex (the side it senses a T-joint's hole on) faces, by clamp orientation.
APEX_TOWARD = {UPRIGHT: 'top', math.pi: 'left', 0.0: 'right'}
#: goal code -> (kind, what it is called, server state (Fig 4.2),
#: {option: (direction, clamps allowed before it)}).
#: A turn needs the clamp of pirate.sequencer.junctions.required_clamp; straight
#: on through a T-joint, the clamp facing its open side (the same module's
#: FACING_OPEN_SIDE), the first of three the goal may start from.
JUNCTIONS = {
    codes.MITRE_BEND: ('mitre', 'mitre bend', 'Taking Mitre bend', {
        codes.LEFT: ('left', ('sideways LEFT',)), codes.RIGHT: ('right', ('sideways RIGHT',)),
        codes.UP: ('up', ('straight',)), codes.DOWN: ('down', ('straight',))}),
    codes.T_JOINT: ('tee', 'T-joint', 'Taking T-joint', {
        codes.LEFT: ('left', ('sideways LEFT',)), codes.RIGHT: ('right', ('sideways RIGHT',)),
        codes.STRAIGHT: ('straight', ('straight', 'sideways LEFT', 'sideways RIGHT'))}),
}
#: (kind, direction) this PAB takes today; the rest are refused with the reason.
TAKEN = {('tee', 'straight'), ('mitre', 'left'), ('mitre', 'right'), ('tee', 'left'), ('tee', 'right')}
#: (kind, direction) it takes rear first too: a goal with a negative search
#: distance, the robot driving backwards out of the network with the rear
#: part leading (the same table, :func:`pirate.sequencer.pabs.junction_table.machine`).
TAKEN_REAR_FIRST = {('tee', 'straight'), ('mitre', 'left'), ('mitre', 'right')}
#: Why a direction taken front first is not taken rear first (twin, 90 mm,
#: from where the front-first turn leaves the robot; doc/sequencer.md, Rear first).
NOT_TAKEN_REAR_FIRST = {
    ('tee', 'left'): 'the rear module has no tilt and is not actuated (report 2.4.1.2), so only a wall turns the '
                     "rear into a T-joint's opening: backing along the run past the branch nothing does and it rode "
                     'on into the open run (1200 mm of odometry, the rear never turned); backing out of the branch '
                     "into the run the run's far wall turned it in 3 of 4 tries (90 mm right: it went into the "
                     "run's open side), too few to take it; a mitre bend's far wall turns it every time",
}
NOT_TAKEN_REAR_FIRST[('tee', 'right')] = NOT_TAKEN_REAR_FIRST[('tee', 'left')]
#: Why a direction of a junction kind is not taken (tried in the twin; what a
#: clamp holds in a steep pipe: bench/vertical_hold).
NOT_TAKEN = {
    'up': 'taking a bend up is not built: it leaves the front V alone carrying the robot in the pipe above, and '
          'in the twin one V alone does not hold the robot in a pipe 45 deg steep or more in 90 mm, 60 deg in '
          '110 mm: it slid back once the rear let go (bench/vertical_hold); and in a vertical pipe the roll the '
          'clamps steer by is not defined',
    'down': "steering down needs the V's apex down: the front tilt stops at -0.1 rad and no clamp holds the "
            'robot upside down',
}


def straight_sideways_problem(guards, speed):
    """Why straight on through a T-joint lying on a side cannot run at
    ``speed`` mm/s in ``guards``' diameter, or None."""
    low = guards.row('junction').get('straight_sideways_speed_min')
    if low is None:
        return ('straight on lying on a side is not taken in a %d mm pipe: config/guards_%d.yaml junction has no '
                'straight_sideways_speed_min (not measured in the twin); past a T-joint open to a side, Clamp '
                'Straight and Drive instead (upright no wheel meets its hole: bench/tee_drive_past)'
                % (guards.pipe_diameter, guards.pipe_diameter))
    if speed < float(low):
        return ('straight on lying on a side needs at least %g mm/s (config/guards_%d.yaml junction '
                'straight_sideways_speed_min; in the twin searching slower, the open front part stalled at the hole)'
                % (float(low), guards.pipe_diameter))
    return None


#: How a goal says which part leads: the sign of its search distance (Pirate.action's ``distance``, signed as
#: a Drive's: negative drives backwards, the rear part leading; 0 is the default distance, front first).
LEAD_BY_SIGN = 'negative: backwards, the rear leading'

#: Why a turn's speed has a range (config/guards_<mm>.yaml turn goal_speed_min / goal_speed_max;
#: bench/junction_turn_probe --speed).
SPEED_WHY = ("measured in the twin: faster, the rear's wheels pushed the front V, clamped at the corner, on "
             'along the new pipe and the middle never swung round (90 mm; at 30 mm/s a robot of stronger wheels '
             "drawn from the twin's ranges), or the front stood up to 140 s against a mitre's far wall (110 mm); "
             'slower, the drive into the new pipe stood (90 mm) or a T-joint was clamped short of its corner or '
             'rolled off the side (110 mm)')


#: What a resumed turn says it went on with, by the record's fact ('{trail}': the trailing part).
RESUMED_TEXT = {'trail_through': 'clamping the {trail} that had come through',
                'driving_in': 'the drive into the new pipe',
                'driven_in': 'straightening after the drive into the new pipe'}


class JunctionMissing(PabFailed):
    """No junction within the goal's distance (the result says junction_missing)."""


def lead_of(goal):
    """The part that leads through the junction (:data:`LEAD_BY_SIGN`): 'rear' for a negative search distance."""
    return 'rear' if goal.distance < 0 else 'front'


class TakeJunction(Pab):
    """Take the junction ahead of ``lead`` ('front': forwards; 'rear':
    backwards): ``kind`` 'mitre' or 'tee', ``direction`` or None (bad option)."""

    @classmethod
    def for_goal(cls, goal):
        kind, label, name, options = JUNCTIONS[goal.name]
        direction, clamps = options.get(goal.option, (None, ()))
        return cls(kind, label, name, direction, clamps, lead_of(goal))

    @classmethod
    def takes(cls, name, option, rear_first=False):
        direction = JUNCTIONS[name][3].get(option, (None,))[0]
        return (JUNCTIONS[name][0], direction) in (TAKEN_REAR_FIRST if rear_first else TAKEN)

    def __init__(self, kind, label, name, direction, clamps, lead='front'):
        self.kind, self.label, self.name, self.direction, self.clamps = kind, label, name, direction, clamps
        self.lead = motions.Lead.of(lead)
        self.machine = MACHINES[lead]
        self.junction_odometry = math.nan       # mm from the goal's start (result field)
        self.junction_missing = False
        self.sensor = None
        self.steered = None          # the RobotView in which the front had turned into the new pipe
        self.start_mm = None
        self.carried = None          # PastCorner: the server's record of this goal's last run
        self.past = None             # PastCorner of this run, once its rear came round
        self.backed_off = 0          # times the steering backed off an edge
        self.target_rad = None       # roll of the clamp held at the start (:meth:`_target`)

    # --- what an unfinished run leaves ------------------------------------------
    def carry_on(self, record):
        """The :class:`PastCorner` this same goal's last run left (:meth:`unfinished`)."""
        self.carried = record

    def unfinished(self):
        """A turn that did not succeed once its rear had come round: its
        :class:`PastCorner`, for the same goal re-sent; else None."""
        return self.past

    @classmethod
    def record_from(cls, data):
        """A :class:`PastCorner` from ``data`` ({'fact', 'from_mm', 'to_mm'}, optional 'lead', default 'front')."""
        fact, from_mm, to_mm = data['fact'], float(data['from_mm']), float(data['to_mm'])
        lead = data.get('lead', 'front')
        if fact not in RESUMED_TEXT:
            raise ValueError('fact %r is none of %s' % (fact, ', '.join(sorted(RESUMED_TEXT))))
        if lead not in table.LEADS:
            raise ValueError('lead %r is none of %s' % (lead, ', '.join(sorted(table.LEADS))))
        if not math.isfinite(from_mm) or not math.isfinite(to_mm) or from_mm > to_mm:
            raise ValueError('odometry span %g .. %g mm is not one' % (from_mm, to_mm))
        return PastCorner(fact, from_mm, to_mm, lead)

    def _carried_facts(self, guards, view):
        """The record's fact, while the odometry lies in its span (give or
        take the drive's tolerance, mm)."""
        record, tolerance = self.carried, float(guards.drive['tolerance'])
        if not self.turning or record is None or record.lead != self.lead.part or not (
                record.from_mm - tolerance <= view.odometry <= record.to_mm + tolerance):
            return {}
        return {record.fact: True}

    # --- accepting ----------------------------------------------------------
    def check(self, goal, view, guards):
        options = JUNCTIONS[goal.name][3]
        allowed = ' / '.join(codes.OPTION_NAMES[o] for o in sorted(options))
        if self.direction is None:
            return 'a %s is taken %s, not %s' % (self.label, allowed,
                                                 codes.OPTION_NAMES.get(goal.option, goal.option))
        rear_first = self.lead.part == 'rear'
        if not self.takes(goal.name, goal.option, rear_first):
            return ('%s %s%s is not yet taken by this PAB (%s; taken today%s: %s)'
                    % (self.label, self.direction.upper(), ' rear first' if rear_first else '',
                       not_taken_why(self.kind, self.direction, rear_first), ' rear first' if rear_first else '',
                       _taken_text(rear_first)))
        if not guards.has('junction'):
            return 'no junction guards for a %d mm pipe' % guards.pipe_diameter
        if self.turning and not guards.has('turn'):
            return 'no turn guards for a %d mm pipe (config/guards_%d.yaml has no turn row)' % (
                guards.pipe_diameter, guards.pipe_diameter)
        speed = motions.search_speed(goal, guards)
        # a turn's own measured range first: it says more than the drive's limits
        return (self._check_distance(goal, guards) or (self.turning and _turn_speed_problem(goal, guards))
                or speed_problem(speed, speed, guards.drive) or self._check_clamp(view, guards)
                or self._check_straight_on_side(view, guards, speed))

    def _check_straight_on_side(self, view, guards, speed):
        """Straight on from a sideways clamp: taken where its row says, at its speeds."""
        if self.turning or self._target(view, guards) == UPRIGHT:
            return None
        return straight_sideways_problem(guards, speed)

    @staticmethod
    def _check_distance(goal, guards):
        limit = float(guards.row('junction')['max_search_mm'])
        if not math.isfinite(goal.distance) or abs(goal.distance) > limit:
            return ('junction search distance %r mm outside [-%.0f, %.0f] mm (0: the default; %s)'
                    % (goal.distance, limit, limit, LEAD_BY_SIGN))
        return None

    def _check_clamp(self, view, guards):
        """Accept a robot the table can start (or, for a turn, resume) from;
        else the reason, saying where in a corner the robot senses it is."""
        facts = self.sensed_facts(guards, view)
        corner = corner_sensing.text(view, facts._asdict(), self.lead)
        if self.turning:
            if first_step(facts, self.lead.part) is not None:
                return None
            return self._turn_refusal(view, guards, facts, corner)
        sensed = clamp_state.sensed(guards, view)
        if corner:
            return self._start_text(view, guards) + (
                '; it is half round a corner toward the %s (%s): re-send that turn to finish it'
                % (corner_sensing.side_turned(guards, view), corner))
        if sensed != (clamp_state.FULL, clamp_state.FULL) or not self._held(view, guards):
            return '%s; %s first' % (self._start_text(view, guards), self._clamp_first(view, guards))
        return None

    def _clamp_first(self, view, guards):
        """The Clamp PAB to send before straight on: the allowed clamp whose
        nominal region holds the roll (on a side only where the guards take
        straight on lying there), else Clamp Straight."""
        for name in self._within(view, guards, 'nominal'):
            if ORIENTATIONS[name] == UPRIGHT:
                return 'Clamp Straight'
            if straight_sideways_problem(guards, float('inf')) is None:
                return 'Clamp Sideways %s' % name.split()[1]
        return 'Clamp Straight'

    def _start_text(self, view, guards):
        return ('%s %s starts clamped %s (report 4.7.4); the robot is %s at %.2f rad'
                % (self.label, self.direction.upper(), ' or '.join(self.clamps),
                   clamp_state.idle_state(clamp_state.sensed(guards, view)), view.orientation))

    def _turn_refusal(self, view, guards, facts, corner):
        """Why a turn can neither start nor resume from what the robot senses."""
        clamp = 'Clamp Sideways %s' % self.direction.upper()
        if corner and not facts.toward:
            side = corner_sensing.side_turned(guards, view)
            return ('%s %s cannot finish this turn: the robot is half round a corner toward the %s (%s; roll %.2f '
                    'rad): re-send the turn toward the %s' % (self.label, self.direction.upper(), side, corner,
                                                              view.orientation, side))
        if corner:
            return ('%s %s cannot finish the turn from here: half round the corner (%s) with the robot %s; it '
                    'resumes with the rear clamped before the middle has swung, or the front clamped after'
                    % (self.label, self.direction.upper(), corner,
                       clamp_state.idle_state(clamp_state.sensed(guards, view))))
        if facts.toward and facts.lead and not facts.trail:
            return ('%s; %s first (a turn cancelled while clamping its trailing part past the corner reads the same: '
                    '%s then ends it there, %.0f mm short of its end; the robot cannot sense which)'
                    % (self._start_text(view, guards), clamp, clamp, float(guards.row('turn')['drive_in_mm'])))
        return '%s; %s first' % (self._start_text(view, guards), clamp)

    def sensed_facts(self, guards, view, found=False):
        """:data:`Facts` of the robot in ``view`` for this goal (``found``: the PAB's own, not sensed)."""
        sensed = clamp_state.sensed(guards, view)._asdict()
        corner = corner_sensing.facts(guards, view, self.lead)
        return Facts(found=found, lead=sensed[self.lead.part] == clamp_state.FULL,
                     trail=sensed[self.lead.trail] == clamp_state.FULL,
                     straight=in_region(view.orientation, region_around(guards, 'straight',
                                                                        self._target(view, guards))),
                     turn=self.turning,
                     toward=in_region(view.orientation, region_around(guards, 'nominal', self._target())),
                     **dict(corner, **self._carried_facts(guards, view)))

    def _target(self, view=None, guards=None):
        """The roll (rad) of the clamp this goal starts in: the side of a
        turn; straight on, the allowed clamp whose straight (else nominal)
        region held the robot's roll the first time a ``view`` was read (the
        goal's start; the clamp it ends in), else the first allowed one."""
        if self.target_rad is None and view is not None:
            held = self._held(view, guards)
            self.target_rad = held[0] if held else None
        return ORIENTATIONS[self.clamps[0]] if self.target_rad is None else self.target_rad

    def _held(self, view, guards):
        """Orientations (rad) of the allowed clamps whose straight region holds
        the robot's roll, else of those whose nominal region does (a clamp a
        drive rolled, which the table re-adjusts first)."""
        held = self._within(view, guards, 'straight') or self._within(view, guards, 'nominal')
        return [ORIENTATIONS[name] for name in held]

    def _within(self, view, guards, region):
        """Names of the allowed clamps whose ``region`` (Table 5.4) holds the robot's roll."""
        return [name for name in self.clamps
                if in_region(view.orientation, region_around(guards, region, ORIENTATIONS[name]))]

    @property
    def turning(self):
        """True when the goal steers into a new pipe (a direction of junctions.TURNS)."""
        return self.direction in TURNS

    # --- running --------------------------------------------------------------
    def actions(self):
        lead = self.lead
        by_template = {
            table.CHANGE_MODES: self._change_modes,
            table.SEARCHING: self._search,
            table.STOPPING: stop_wheels,
            table.UNCLAMPING_LEAD: self._unclamp_lead,
            table.CROSSING_LEAD: lambda ctx: motions.drive_across(ctx, lead.part, lead),
            table.CLAMPING_LEAD: lambda ctx: motions.clamp_full(ctx, lead.part),
            table.UNCLAMPING_TRAIL: lambda ctx: motions.open_to_cross(ctx, lead.trail, lead),
            table.CROSSING_TRAIL: lambda ctx: motions.drive_across(ctx, lead.trail, lead),
            table.CLAMPING_TRAIL: lambda ctx: motions.clamp_full(ctx, lead.trail),
            table.STRAIGHTENING: lambda ctx: Clamp(self._target()).run(ctx),
            table.RE_ADJUSTING: lambda ctx: Clamp(self._target()).run(ctx),
            table.LIFTING_LEAD: lambda ctx: ctx.prims.move_front('move_front_turn'),
            table.STEERING_LEAD: self._steer_lead,
            table.CLAMPING_LEAD_AT_CORNER: lambda ctx: motions.clamp_at_corner(ctx, lead),
            table.SWINGING_MIDDLE: lambda ctx: motions.swing_middle(ctx, lead),
            table.BRINGING_TRAIL: self._bring_trail_and_record,
            table.DRIVING_IN: self._drive_in,
        }
        actions = {table.state(template, lead.part): action for template, action in by_template.items()}
        return {name: actions[name] for name in self.machine.states if name in actions}

    def _unclamp_lead(self, ctx):
        """Straight on, ready the leading part to cross (:func:`~pirate.sequencer.pabs.turn_motions.open_to_cross`).
        A turn opens the leading V partly, then levels the leading part on its
        side where its row says (``level_front``, :func:`~pirate.sequencer.pabs.turn_motions.level_front`). Only
        here, at a turn's start: a turn resumed into its steering does not
        level (twin, 110 mm T-joint entered through its run, re-sent after a
        cancel while steering: levelled again, the rear's roll drifted to
        2.94 rad, past the band of the sideways clamp, and its clamp past the
        corner timed out in 6 of 10)."""
        if not self.turning:
            motions.open_to_cross(ctx, self.lead.part, self.lead)
            return
        ctx.prims.unclamp(self.lead.part, partial=True)
        if ctx.guards.row('turn').get('level_front'):
            motions.level_front(ctx, self._target(), self.lead)

    def facts(self, ctx):
        found = self.steered is not None or (self.sensor is not None and self.sensor.sensed is not None)
        return self.sensed_facts(ctx.guards, ctx.feed.latest(), found)

    def _change_modes(self, ctx):
        """Rotation in position, front module in PWM; a turn presses its clamped
        parts again, and keeps the server's record only if it holds here."""
        if self._carried_facts(ctx.guards, ctx.feed.latest()):
            self.past = self.carried         # cancelled again, the same record stands
        else:
            self.carried = None
        ctx.prims.change_control_mode('rotation', 'position')
        ctx.prims.change_control_mode('front_tilt', 'pwm')
        if self.turning:
            motions.press_what_is_clamped(ctx)

    def _bring_trail_and_record(self, ctx):
        """:func:`~pirate.sequencer.pabs.turn_motions.bring_trail`, then the record that the trailing part came
        through."""
        motions.bring_trail(ctx, self.lead)
        now = ctx.feed.latest().odometry
        self.past = PastCorner('trail_through', now, now, self.lead.part)

    def _drive_in(self, ctx):
        """Drive on ``drive_in_mm`` so the rear module leaves the corner too;
        resumed in it (:attr:`carried`), only what is left of that drive,
        nothing when less than the drive's tolerance is."""
        now, sign = ctx.feed.latest().odometry, self.lead.sign
        resumed = self.carried is not None and self.carried.fact == 'driving_in'
        span = ((self.carried.from_mm, self.carried.to_mm) if resumed
                else sorted((now, now + sign * float(ctx.guards.row('turn')['drive_in_mm']))))
        end = span[1] if sign > 0 else span[0]          # the planned end, the way the lead goes
        self.past = PastCorner('driving_in', span[0], span[1], self.lead.part)
        if sign * (end - now) > float(ctx.guards.drive['tolerance']):
            motions.drive_by(ctx, 'drive into the new pipe', sign * (end - now), lead=self.lead)
        # to where the wheels stopped: a few mm past the planned end (110 mm twin: +8)
        stopped = ctx.feed.latest().odometry
        self.past = PastCorner('driven_in', min(span[0], stopped), max(span[1], stopped), self.lead.part)

    def _search(self, ctx):
        """Drive until the junction is sensed, or JunctionMissing after the goal's distance."""
        row = ctx.guards.row('junction')
        lead = self.lead
        distance = abs(ctx.goal.distance) or float(row['search_mm'])
        start = ctx.feed.latest()
        self.start_mm, self.sensor = start.odometry, JunctionSensor(ctx.guards, start, lead.part)
        progress = Progress(ctx.guards.drive, start)
        speed = motions.search_speed(ctx.goal, ctx.guards)
        ctx.prims.drive_at_velocity(lead.sign * speed)
        view = ctx.prims.wait_for(
            'look for the junction',
            lambda v: progress.check(v) and (self.sensor.update(v) or lead.along(v, start) >= distance),
            '%s V loses its wall, or odometry %+.0f mm' % (lead.part, lead.sign * distance),
            motions.time_bound(ctx, distance, speed))
        if self.sensor.sensed is None:
            self.junction_missing = True
            raise JunctionMissing('no junction within %.0f mm (odometry %+.0f mm from the start; the %s V, its '
                                  'apex toward the %s, kept its wall: a T-joint open another way is not sensed from '
                                  'this clamp, e.g. upright one open to a side, which a Drive passes)'
                                  % (distance, view.odometry - self.start_mm, lead.part,
                                     APEX_TOWARD[self._target()]))
        self.junction_odometry = self.sensor.sensed.odometry - self.start_mm

    def _steer_lead(self, ctx):
        """Drive with the leading V open and its bends toward the turn side
        (the front leading: the front tilt keeping the front module pointed
        along the new pipe, pi/2 - Bend I - Bend II), until the leading V's
        inner bend says the leading part has turned into the new pipe
        (:meth:`_steer_until_round`). In a straight pipe the walls keep it far
        below ``steered_rad``: JunctionMissing once the odometry is
        :func:`steer_reach_mm` from the start, or after the steering's time
        bound."""
        row, prims, lead = motions.turn_row(ctx.guards, self.lead), ctx.prims, self.lead
        distance = abs(ctx.goal.distance) or float(ctx.guards.row('junction')['search_mm'])
        limit_s = (float(row['steer_base_s']) + float(row['steer_s_per_mm']) * distance) * motions.slower(ctx.goal, row)
        start = ctx.feed.latest()
        self.start_mm = start.odometry
        motions.torque(prims, **{lead.outer: int(row['steer_bend_i']), lead.inner: int(row['steer_bend_ii'])})
        reach_mm = steer_reach_mm(ctx.goal, ctx.guards, row)
        try:
            view = self._steer_until_round(ctx, row, start, start.stamp + limit_s, reach_mm)
        except TimedOut:
            view = None
        finally:
            prims.drive_at_velocity(0.0)
            if lead.part == 'front':
                prims.move_module('front_tilt', 0)
        if view is None:
            self.junction_missing = True
            last = ctx.feed.latest()
            raise JunctionMissing('no opening toward the %s within %.0f mm (odometry %+.0f mm in %.0f s of steering; '
                                  'the %s did not turn%s)' % (
                                      self.direction, reach_mm, last.odometry - start.odometry,
                                      last.stamp - start.stamp, lead.part, motions.backed_off_text(self.backed_off)))
        self.steered = view
        self.junction_odometry = view.odometry - start.odometry

    def _steer_until_round(self, ctx, row, start, end, last_mm):
        """Steer on until the leading part is round the corner (the view then),
        or None once the odometry has gone ``last_mm`` from ``start`` the way it
        leads; TimedOut at robot time ``end``. Wheels that stand
        ``back_off_after_s`` on end say the leading part has met an edge it
        does not get past: the far edge of an opening it
        did not drop into, or the end of the run it rode on past one. It
        backs off ``back_off_mm`` and steers on: the bends, still toward the
        turn side, carry the leading module further toward the opening while
        it backs, and it meets the edge again deeper in (twin, 110 mm T-joint
        entered through its run: the front stood 40 s at the opening's far
        edge, rode on past and stood at the run's end for the rest of the
        goal; backed off 40 mm after 8 s it turned into the branch:
        bench/pab_junction_sweep)."""
        prims, speed, lead = ctx.prims, motions.turn_speed(ctx.goal, row), self.lead
        stand_s = float(row['back_off_after_s'])
        while True:
            standing = motions.Standing(stand_s)
            prims.drive_at_velocity(lead.sign * speed)
            view = prims.follow('steer %s' % lead.part, motions.steer_tilt(prims, row, lead),
                                lambda v: (motions.steered(row, v, lead) or standing.long(v)
                                           or lead.along(v, start) > last_mm),
                                '%s (or the wheels standing %g s: back off; or odometry past %+.0f mm)'
                                % (motions.steered_text(row, lead), stand_s, lead.sign * last_mm),
                                motions.left_s(ctx, end))
            if motions.steered(row, view, lead):
                return view
            if lead.along(view, start) > last_mm:
                return None
            self.backed_off += 1
            motions.back_off(ctx, row, speed, end, lead)

    def summary(self, ctx):
        if self.carried is not None:
            return ('%s: resumed past the corner (%s), %d motion primitives, ended clamped'
                    % (self._what(), RESUMED_TEXT[self.carried.fact].format(trail=self.lead.trail),
                       len(ctx.prims.executed)))
        if math.isnan(self.junction_odometry):
            return ('%s: resumed where the robot stood in the corner, %d motion primitives, ended clamped'
                    % (self._what(), len(ctx.prims.executed)))
        why = (self.sensor.sensed.why if self.sensor is not None
               else 'the %s turned into the new pipe' % self.lead.part)
        why += motions.backed_off_text(self.backed_off)
        return ('%s: junction sensed %+.0f mm after the start (%s), %d motion primitives, ended clamped'
                % (self._what(), self.junction_odometry, why, len(ctx.prims.executed)))

    def _what(self):
        return '%s %s%s' % (self.kind, self.direction, ', rear first' if self.lead.part == 'rear' else '')


def steer_reach_mm(goal, guards, row):
    """How far (mm of odometry) a turn steers before its leading part must
    be round the corner: the goal's distance, which bounds it as it bounds
    the search straight on (a mission's map says how far the junction can
    be); 0, the junction row's ``search_mm`` plus the turn row's
    ``steer_beyond_mm`` (the leading part turns round that far after it
    reaches the opening)."""
    if goal.distance:
        return abs(goal.distance)
    return float(guards.row('junction')['search_mm']) + float(row['steer_beyond_mm'])


def not_taken_why(kind, direction, rear_first=False):
    """Why the PAB does not take ``kind`` (mitre / tee) ``direction`` (rear first when ``rear_first``)."""
    if rear_first and (kind, direction) in NOT_TAKEN_REAR_FIRST:
        return NOT_TAKEN_REAR_FIRST[(kind, direction)]
    return NOT_TAKEN.get(direction, 'not built')


def _taken_text(rear_first=False):
    return ', '.join('%s %s' % (kind, direction.upper())
                     for kind, direction in sorted(TAKEN_REAR_FIRST if rear_first else TAKEN))


def _turn_speed_problem(goal, guards):
    """Why a turn cannot run at the goal's speed (the turn row's range, measured
    in the twin), or None; a range that is not low <= steer_speed <= high is a
    bad guard file, named."""
    row, where = guards.row('turn'), 'config/guards_%d.yaml turn' % guards.pipe_diameter
    try:
        low, default, high = (float(row[key]) for key in ('goal_speed_min', 'steer_speed', 'goal_speed_max'))
    except (KeyError, TypeError, ValueError) as bad:
        return '%s: goal_speed_min / steer_speed / goal_speed_max must be numbers (mm/s): %s' % (where, bad)
    if not 0.0 < low <= default <= high:
        return ('%s: goal_speed_min %g <= steer_speed %g <= goal_speed_max %g mm/s does not hold'
                % (where, low, default, high))
    if goal.speed and not low <= goal.speed <= high:
        return ('a turn is taken at %g to %g mm/s (0: %g mm/s), not %g mm/s (%s goal_speed_min / goal_speed_max; '
                '%s)' % (low, high, default, goal.speed, where, SPEED_WHY))
    return None
