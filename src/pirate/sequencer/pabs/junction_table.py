"""Take T-joint / Take mitre bend: the transition table (report Table D.1's form).

One table serves both junction kinds, every direction the PAB takes and
either part leading: the front (driving forwards, into the network) or the
rear (driving backwards, the way the robot came). :func:`machine` builds it
for the leading part; the facts name the parts by their role (``lead``,
``trail``), what each state and fact is called names the part. Straight on
(a T-joint): search until the leading V loses its wall, then each part
crosses open while the other holds. A turn (left / right): steer the
leading part into the new pipe, clamp it at the corner, swing the middle,
bring the trailing part through, clamp both and drive in. A turn cancelled
on the way and re-sent resumes from CHANGE_MODES at the step that
continues it, chosen by the corner facts the robot senses and by the
server's record of the same goal (``trail_through``, ``driving_in``,
``driven_in``). A clamp a drive rolled out of its straight region, but not
out of the nominal one, is re-adjusted first.

What each state does: :mod:`pirate.sequencer.pabs.junction`. The tables as
printed: doc/sequencer.md (``make docs``). Pure.
"""
import collections

from pirate.sequencer.pabs.base import ALWAYS, END, StateMachine, Transition
from pirate.sequencer.pabs.expr import all_of, any_of, fact, named, not_

#: The parts, by which one leads: (leading, trailing).
LEADS = {'front': ('front', 'rear'), 'rear': ('rear', 'front')}
#: What each part's bends are called: the V's inner bend (the one round a
#: corner first), and the inner bend of the other part's V (the middle's swing).
INNER_BEND = {'front': 'Bend II', 'rear': 'Bend III'}
OUTER_BEND = {'front': 'Bend I', 'rear': 'Bend IV'}
#: The part whose module tilts toward a turn before it steers (only the front module has a tilt).
TILTS = ('front',)

#: The states, by the leading part ('{lead}', '{trail}': the parts' names).
CHANGE_MODES = 'change control modes'
SEARCHING = 'looking for the junction'
STOPPING = 'stopping'
UNCLAMPING_LEAD = 'unclamping {lead} partial'
CROSSING_LEAD = 'driving the {lead} across'
CLAMPING_LEAD = 'clamping {lead}'
UNCLAMPING_TRAIL = 'unclamping {trail} partial'
CROSSING_TRAIL = 'driving the {trail} across'
CLAMPING_TRAIL = 'clamping {trail}'
STRAIGHTENING = 'straightening (Clamp Straight)'
LIFTING_LEAD = 'lifting the {lead} toward the turn'
STEERING_LEAD = 'steering the {lead} into the new pipe'
CLAMPING_LEAD_AT_CORNER = 'clamping {lead} at the corner'
SWINGING_MIDDLE = 'swinging the middle round'
BRINGING_TRAIL = 'bringing the {trail} through'
DRIVING_IN = 'driving into the new pipe'
RE_ADJUSTING = 're-adjusting the clamp'
STATES = (CHANGE_MODES, SEARCHING, STOPPING, UNCLAMPING_LEAD, CROSSING_LEAD, CLAMPING_LEAD, UNCLAMPING_TRAIL,
          CROSSING_TRAIL, CLAMPING_TRAIL, STRAIGHTENING, LIFTING_LEAD, STEERING_LEAD, CLAMPING_LEAD_AT_CORNER,
          SWINGING_MIDDLE, BRINGING_TRAIL, DRIVING_IN, RE_ADJUSTING)


def state(template, lead):
    """The state ``template`` (one of :data:`STATES`) named for ``lead`` leading."""
    return template.format(lead=lead, trail=LEADS[lead][1])


#: The facts, read after every action. Remembered facts hold only while the
#: odometry lies within the record's span: a robot moved since is not resumed.
Facts = collections.namedtuple('Facts', 'found lead trail straight turn toward lead_round corner_opening '
                                        'middle_round middle_swung trail_round trail_through driving_in driven_in',
                               defaults=(False,) * 9)

#: The remembered facts a turn's record makes true (:class:`pirate.sequencer.pabs.junction.PastCorner`).
REMEMBERED = ('trail_through', 'driving_in', 'driven_in')


def _facts(lead):
    """The facts (expressions) of the table with ``lead`` leading, by field."""
    trail = LEADS[lead][1]
    middle = INNER_BEND[trail]
    return dict(
        found=fact('found', 'junction sensed', 'the junction was sensed (straight on: the %s V lost its wall; a '
                                               'turn: %s round the corner)' % (lead, INNER_BEND[lead])),
        lead=fact('lead', '%s clamped' % lead, 'the %s part (leading) is clamped full, as the robot senses it '
                                               '(angles and spring)' % lead),
        trail=fact('trail', '%s clamped' % trail, 'the %s part (trailing) is clamped full, as the robot senses it'
                   % trail),
        straight=fact('straight', means="the rear's roll within Table 5.4's straight region around the clamp the "
                                        'goal started in'),
        turn=fact('turn', means='the goal turns into a new pipe (the goal says so; not sensed)'),
        toward=fact('toward', means="the rear's roll within the nominal region around the clamp of the goal's side"),
        lead_round=fact('lead_round', '%s_round' % lead, '%s round the corner: the %s has turned into the new pipe'
                        % (INNER_BEND[lead], lead)),
        corner_opening=fact('corner_opening', means="%s round the corner below the turn row's corner_inner_rad with "
                                                    '%s pressing the wall: clamped at the corner, the middle swinging '
                                                    'round opened it' % (INNER_BEND[lead], OUTER_BEND[lead])),
        middle_round=fact('middle_round', means="%s at least the turn row's resume_middle_rad: the middle swinging "
                                                'round (a straight pipe keeps it below)' % middle),
        middle_swung=fact('middle_swung', means="%s at least the turn row's swing_rad" % middle),
        trail_round=fact('trail_round', '%s_round' % trail, "%s at least the turn row's resume_rear_rad: the %s V "
                                                            'coming round' % (OUTER_BEND[trail], trail)),
        trail_through=fact('trail_through', '%s_through' % trail, "remembered: the goal's last run ended after "
                                                                  'bringing the %s through' % trail),
        driving_in=fact('driving_in', means="remembered: the goal's last run ended while driving into the new pipe"),
        driven_in=fact('driven_in', means="remembered: the goal's last run ended after driving into the new pipe"),
    )


def machine(lead):
    """The junction PAB's :class:`StateMachine` with ``lead`` ('front' / 'rear') leading."""
    f = _facts(lead)
    s = {template: state(template, lead) for template in STATES}
    in_a_corner = named('in a corner', any_of(f['lead_round'], f['corner_opening'], f['middle_round'],
                                              f['middle_swung'], f['trail_round']),
                        'some bend says the robot is (partly) round a corner')
    past_the_corner = named('past the corner', any_of(f['trail_through'], f['driving_in'], f['driven_in']),
                            "the server's record says this turn's %s had come round the corner" % LEADS[lead][1])
    at_the_start = named('at the start', all_of(not_(in_a_corner), not_(past_the_corner)),
                         'nothing says a turn was under way here')
    on, turn, lead_, trail = not_(f['turn']), f['turn'], f['lead'], f['trail']
    # Straight on from its start: the straight region of the clamp it holds (check() accepts no other).
    on_start = all_of(on, f['straight'])
    # A turn from its start: clamped sideways toward it, no bend round a corner.
    start = all_of(turn, lead_, trail, f['straight'], at_the_start)
    # A clamp a drive rolled out of its straight region, within the nominal one.
    re_adjust = all_of(lead_, trail, not_(f['straight']), f['toward'], at_the_start)
    done = all_of(on, lead_, trail, f['straight'])
    # A turn re-sent after a cancel: the step that continues it from what the robot senses.
    toward = f['toward']
    resume_steering = all_of(turn, toward, trail, not_(lead_), at_the_start)
    swinging = any_of(f['middle_round'], f['corner_opening'])
    resume_at_corner = all_of(turn, toward, trail, f['lead_round'], not_(swinging),
                              not_(f['middle_swung']), not_(past_the_corner))
    resume_swinging = all_of(turn, toward, trail, swinging, not_(f['middle_swung']), not_(past_the_corner))
    resume_bringing = all_of(turn, toward, lead_,
                             any_of(all_of(trail, f['middle_swung']),
                                    all_of(not_(trail), any_of(f['middle_round'], f['middle_swung'],
                                                               f['trail_round']))),
                             not_(past_the_corner))
    resume_clamping = all_of(turn, toward, f['trail_through'], not_(f['driving_in']), not_(f['driven_in']), lead_)
    resume_driving_in = all_of(turn, toward, f['driving_in'], not_(f['driven_in']), lead_, trail)
    resume_straightening = all_of(turn, toward, f['driven_in'])
    # a lead whose module tilts lifts it toward the turn first; the other opens at once
    steer_from = s[LIFTING_LEAD] if lead in TILTS else s[UNCLAMPING_LEAD]
    T = Transition
    rows = [
        T(s[CHANGE_MODES],       s[SEARCHING],          on_start),
        T(s[CHANGE_MODES],       steer_from,            start),
        T(s[CHANGE_MODES],       s[RE_ADJUSTING],       re_adjust),
        T(s[CHANGE_MODES],       s[STEERING_LEAD],      resume_steering),
        T(s[CHANGE_MODES],       s[CLAMPING_LEAD_AT_CORNER], resume_at_corner),
        T(s[CHANGE_MODES],       s[SWINGING_MIDDLE],    resume_swinging),
        T(s[CHANGE_MODES],       s[BRINGING_TRAIL],     resume_bringing),
        T(s[CHANGE_MODES],       s[CLAMPING_TRAIL],     resume_clamping),
        T(s[CHANGE_MODES],       s[DRIVING_IN],         resume_driving_in),
        T(s[CHANGE_MODES],       s[STRAIGHTENING],      resume_straightening),
        T(s[RE_ADJUSTING],       s[SEARCHING],          on_start),
        T(s[RE_ADJUSTING],       steer_from,            start),
        T(s[SEARCHING],          s[STOPPING],           f['found']),
        T(s[STOPPING],           s[UNCLAMPING_LEAD],    ALWAYS)]
    if lead in TILTS:
        rows.append(T(s[LIFTING_LEAD], s[UNCLAMPING_LEAD], ALWAYS))
    rows += [
        T(s[UNCLAMPING_LEAD],    s[CROSSING_LEAD],      on),
        T(s[UNCLAMPING_LEAD],    s[STEERING_LEAD],      turn),
        T(s[CROSSING_LEAD],      s[CLAMPING_LEAD],      ALWAYS),
        T(s[STEERING_LEAD],      s[CLAMPING_LEAD_AT_CORNER], f['found']),
        T(s[CLAMPING_LEAD_AT_CORNER], s[SWINGING_MIDDLE],    ALWAYS),
        T(s[SWINGING_MIDDLE],    s[BRINGING_TRAIL],     ALWAYS),
        T(s[BRINGING_TRAIL],     s[CLAMPING_TRAIL],     ALWAYS),
        T(s[CLAMPING_LEAD],      s[UNCLAMPING_TRAIL],   all_of(on, lead_)),
        T(s[CLAMPING_LEAD],      s[DRIVING_IN],         all_of(turn, lead_)),
        T(s[UNCLAMPING_TRAIL],   s[CROSSING_TRAIL],     ALWAYS),
        T(s[CROSSING_TRAIL],     s[CLAMPING_TRAIL],     ALWAYS),
        T(s[CLAMPING_TRAIL],     END,                   done),
        T(s[CLAMPING_TRAIL],     s[STRAIGHTENING],      all_of(on, lead_, trail, not_(f['straight']))),
        T(s[CLAMPING_TRAIL],     s[CLAMPING_LEAD],      all_of(turn, trail)),
        T(s[DRIVING_IN],         s[STRAIGHTENING],      ALWAYS),
        T(s[STRAIGHTENING],      END,                   ALWAYS),
    ]
    return StateMachine(s[CHANGE_MODES], rows, facts=Facts)


#: The table by leading part: the front leads into the network, the rear out of it.
MACHINES = {lead: machine(lead) for lead in LEADS}
#: The front-first table (the one the report describes).
MACHINE = MACHINES['front']

# The front-first states by name (the rear-first ones: state(template, 'rear')).
UNCLAMPING_FRONT = state(UNCLAMPING_LEAD, 'front')
CROSSING_FRONT = state(CROSSING_LEAD, 'front')
CLAMPING_FRONT = state(CLAMPING_LEAD, 'front')
UNCLAMPING_REAR = state(UNCLAMPING_TRAIL, 'front')
CROSSING_REAR = state(CROSSING_TRAIL, 'front')
CLAMPING_REAR = state(CLAMPING_TRAIL, 'front')
LIFTING_FRONT = state(LIFTING_LEAD, 'front')
STEERING_FRONT = state(STEERING_LEAD, 'front')
BRINGING_REAR = state(BRINGING_TRAIL, 'front')
CLAMPING_AT_CORNER = state(CLAMPING_LEAD_AT_CORNER, 'front')


def _each_lead(*templates):
    return tuple(state(t, lead) for lead in LEADS for t in templates)


#: The states of a turn half round its corner, before the trailing part comes
#: round, either part leading: a turn stopped in one leaves the robot where only
#: the turn can go on.
CORNER_STATES = _each_lead(CLAMPING_LEAD_AT_CORNER, SWINGING_MIDDLE)
#: The states steering the leading part in / bringing the trailing part through, either part leading.
STEERING_STATES = _each_lead(STEERING_LEAD)
BRINGING_STATES = _each_lead(BRINGING_TRAIL)
#: The states entered the moment the junction is sensed (straight on: stopping;
#: a turn: clamping at the corner), either part leading: where a localiser's anchor applies.
SENSED_STATES = tuple(sorted({t.target for table in MACHINES.values() for t in table.transitions
                              if t.guard.text == 'junction sensed'}))


def first_step(facts, lead='front'):
    """The state the table with ``lead`` leading enters from CHANGE_MODES with ``facts``, or None."""
    fired = [t.target for t in MACHINES[lead].exits(CHANGE_MODES) if t.guard.test(facts)]
    return fired[0] if len(fired) == 1 else None
