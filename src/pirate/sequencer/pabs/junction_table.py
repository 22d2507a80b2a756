"""Take T-joint / Take mitre bend: the transition table (report Table D.1's form).

One table serves both junction kinds and every direction the PAB takes.
Straight on (a T-joint): search until the front V loses its wall, then
each part crosses open while the other holds. A turn (left / right):
steer the front into the new pipe, clamp it at the corner, swing the
middle, bring the rear through, clamp both and drive in. A turn cancelled
on the way and re-sent resumes from CHANGE_MODES at the step that
continues it, chosen by the corner facts the robot senses and by the
server's record of the same goal (``rear_through``, ``driving_in``,
``driven_in``). A clamp a drive rolled out of its straight region, but not
out of the nominal one, is re-adjusted first.

What each state does: :mod:`pirate.sequencer.pabs.junction`. The table as
printed: doc/sequencer.md (``make docs``). Pure.
"""
import collections

from pirate.sequencer.pabs.base import ALWAYS, END, StateMachine, Transition
from pirate.sequencer.pabs.expr import all_of, any_of, fact, named, not_

CHANGE_MODES = 'change control modes'
SEARCHING = 'looking for the junction'
STOPPING = 'stopping'
UNCLAMPING_FRONT = 'unclamping front partial'
CROSSING_FRONT = 'driving the front across'
CLAMPING_FRONT = 'clamping front'
UNCLAMPING_REAR = 'unclamping rear partial'
CROSSING_REAR = 'driving the rear across'
CLAMPING_REAR = 'clamping rear'
STRAIGHTENING = 'straightening (Clamp Straight)'
LIFTING_FRONT = 'lifting the front toward the turn'
STEERING_FRONT = 'steering the front into the new pipe'
CLAMPING_AT_CORNER = 'clamping front at the corner'
SWINGING_MIDDLE = 'swinging the middle round'
BRINGING_REAR = 'bringing the rear through'
DRIVING_IN = 'driving into the new pipe'
RE_ADJUSTING = 're-adjusting the clamp'
#: The states of a turn half round its corner, before the rear comes round:
#: a turn stopped in one leaves the robot where only the turn can go on.
CORNER_STATES = (CLAMPING_AT_CORNER, SWINGING_MIDDLE)

# --- the facts, read after every action --------------------------------------
FOUND = fact('found', 'junction sensed', 'the junction was sensed (straight on: the front V lost its wall; '
                                         'a turn: Bend II round the corner)')
FRONT = fact('front', 'front clamped', 'the front part is clamped full, as the robot senses it (angles and spring)')
REAR = fact('rear', 'rear clamped', 'the rear part is clamped full, as the robot senses it')
STRAIGHT = fact('straight', means="the rear's roll within Table 5.4's straight region around the clamp the goal "
                                  'started in')
TURN = fact('turn', means='the goal turns into a new pipe (the goal says so; not sensed)')
TOWARD = fact('toward', means="the rear's roll within the nominal region around the clamp of the goal's side")
FRONT_ROUND = fact('front_round', means='Bend II round the corner: the front has turned into the new pipe')
MIDDLE_ROUND = fact('middle_round', means="Bend III at least the turn row's resume_middle_rad: the middle swinging "
                                          'round (a straight pipe keeps it below)')
MIDDLE_SWUNG = fact('middle_swung', means="Bend III at least the turn row's swing_rad")
REAR_ROUND = fact('rear_round', means="Bend IV at least the turn row's resume_rear_rad: the rear V coming round")
WAS_REAR_THROUGH = fact('rear_through', means="remembered: the goal's last run ended after bringing the rear through")
WAS_DRIVING_IN = fact('driving_in', means="remembered: the goal's last run ended while driving into the new pipe")
WAS_DRIVEN_IN = fact('driven_in', means="remembered: the goal's last run ended after driving into the new pipe")

#: The facts above, in the order the PAB reads them. Remembered facts hold
#: only while the odometry lies within the record's span: a robot moved
#: since is not resumed.
Facts = collections.namedtuple('Facts', 'found front rear straight turn toward front_round middle_round middle_swung '
                                        'rear_round rear_through driving_in driven_in', defaults=(False,) * 8)

IN_A_CORNER = named('in a corner', any_of(FRONT_ROUND, MIDDLE_ROUND, MIDDLE_SWUNG, REAR_ROUND),
                    'some bend says the robot is (partly) round a corner')
PAST_THE_CORNER = named('past the corner', any_of(WAS_REAR_THROUGH, WAS_DRIVING_IN, WAS_DRIVEN_IN),
                        "the server's record says this turn's rear had come round the corner")
AT_THE_START = named('at the start', all_of(not_(IN_A_CORNER), not_(PAST_THE_CORNER)),
                     'nothing says a turn was under way here')

# --- the guards ----------------------------------------------------------------
ON = not_(TURN)
#: Straight on from its start: the straight region of the clamp it holds (check() accepts no other).
ON_START = all_of(ON, STRAIGHT)
#: A turn from its start: clamped sideways toward it, no bend round a corner.
START = all_of(TURN, FRONT, REAR, STRAIGHT, AT_THE_START)
#: A clamp a drive rolled out of its straight region, within the nominal one.
RE_ADJUST = all_of(FRONT, REAR, not_(STRAIGHT), TOWARD, AT_THE_START)
DONE = all_of(ON, FRONT, REAR, STRAIGHT)
# A turn re-sent after a cancel: the step that continues it from what the robot senses.
RESUME_STEERING = all_of(TURN, TOWARD, REAR, not_(FRONT), AT_THE_START)
RESUME_AT_CORNER = all_of(TURN, TOWARD, REAR, FRONT_ROUND, not_(MIDDLE_ROUND), not_(MIDDLE_SWUNG),
                          not_(PAST_THE_CORNER))
RESUME_SWINGING = all_of(TURN, TOWARD, REAR, MIDDLE_ROUND, not_(MIDDLE_SWUNG), not_(PAST_THE_CORNER))
RESUME_BRINGING = all_of(TURN, TOWARD, FRONT,
                         any_of(all_of(REAR, MIDDLE_SWUNG),
                                all_of(not_(REAR), any_of(MIDDLE_ROUND, MIDDLE_SWUNG, REAR_ROUND))),
                         not_(PAST_THE_CORNER))
RESUME_CLAMPING_REAR = all_of(TURN, TOWARD, WAS_REAR_THROUGH, not_(WAS_DRIVING_IN), not_(WAS_DRIVEN_IN), FRONT)
RESUME_DRIVING_IN = all_of(TURN, TOWARD, WAS_DRIVING_IN, not_(WAS_DRIVEN_IN), FRONT, REAR)
RESUME_STRAIGHTENING = all_of(TURN, TOWARD, WAS_DRIVEN_IN)

T = Transition
MACHINE = StateMachine(CHANGE_MODES, (
    # state              next state          guard
    T(CHANGE_MODES,       SEARCHING,          ON_START),
    T(CHANGE_MODES,       LIFTING_FRONT,      START),
    T(CHANGE_MODES,       RE_ADJUSTING,       RE_ADJUST),
    T(CHANGE_MODES,       STEERING_FRONT,     RESUME_STEERING),
    T(CHANGE_MODES,       CLAMPING_AT_CORNER, RESUME_AT_CORNER),
    T(CHANGE_MODES,       SWINGING_MIDDLE,    RESUME_SWINGING),
    T(CHANGE_MODES,       BRINGING_REAR,      RESUME_BRINGING),
    T(CHANGE_MODES,       CLAMPING_REAR,      RESUME_CLAMPING_REAR),
    T(CHANGE_MODES,       DRIVING_IN,         RESUME_DRIVING_IN),
    T(CHANGE_MODES,       STRAIGHTENING,      RESUME_STRAIGHTENING),
    T(RE_ADJUSTING,       SEARCHING,          ON_START),
    T(RE_ADJUSTING,       LIFTING_FRONT,      START),
    T(SEARCHING,          STOPPING,           FOUND),
    T(STOPPING,           UNCLAMPING_FRONT,   ALWAYS),
    T(LIFTING_FRONT,      UNCLAMPING_FRONT,   ALWAYS),
    T(UNCLAMPING_FRONT,   CROSSING_FRONT,     ON),
    T(UNCLAMPING_FRONT,   STEERING_FRONT,     TURN),
    T(CROSSING_FRONT,     CLAMPING_FRONT,     ALWAYS),
    T(STEERING_FRONT,     CLAMPING_AT_CORNER, FOUND),
    T(CLAMPING_AT_CORNER, SWINGING_MIDDLE,    ALWAYS),
    T(SWINGING_MIDDLE,    BRINGING_REAR,      ALWAYS),
    T(BRINGING_REAR,      CLAMPING_REAR,      ALWAYS),
    T(CLAMPING_FRONT,     UNCLAMPING_REAR,    all_of(ON, FRONT)),
    T(CLAMPING_FRONT,     DRIVING_IN,         all_of(TURN, FRONT)),
    T(UNCLAMPING_REAR,    CROSSING_REAR,      ALWAYS),
    T(CROSSING_REAR,      CLAMPING_REAR,      ALWAYS),
    T(CLAMPING_REAR,      END,                DONE),
    T(CLAMPING_REAR,      STRAIGHTENING,      all_of(ON, FRONT, REAR, not_(STRAIGHT))),
    T(CLAMPING_REAR,      CLAMPING_FRONT,     all_of(TURN, REAR)),
    T(DRIVING_IN,         STRAIGHTENING,      ALWAYS),
    T(STRAIGHTENING,      END,                ALWAYS),
), facts=Facts)

#: The states entered the moment the junction is sensed (straight on: stopping;
#: a turn: clamping at the corner): where a localiser's anchor applies.
SENSED_STATES = tuple(t.target for t in MACHINE.transitions if t.guard is FOUND)


def first_step(facts):
    """The state the table enters from CHANGE_MODES with ``facts``, or None."""
    fired = [t.target for t in MACHINE.exits(CHANGE_MODES) if t.guard.test(facts)]
    return fired[0] if len(fired) == 1 else None
