"""Clamp Straight's transition table (SPEC 8, Table D.1), as data.

- the table prints and every state is reachable;
- exhaustively over every combination of Facts, at most one transition
  fires per state, and exactly one when the facts agree with what the
  state's own action just did (a clamp state leaves its part clamped ...);
- the fact sequences of the report's three experiments walk exactly the
  step lists of Tables 6.1-6.3 (transcribed here from SPEC 8).
"""
import itertools

import pytest

from pirate.sequencer.pabs import clamp as cs
from pirate.sequencer.pabs import drive, home
from pirate.sequencer.pabs.base import ALWAYS, END, PabFailed, StateMachine, Transition

MACHINE = cs.MACHINE
NONE, CUSTOM, FULL = cs.NONE, cs.CUSTOM, cs.FULL

ALL_FACTS = [cs.Facts(*values) for values in itertools.product(
    (True, False), (True, False), (True, False), (NONE, CUSTOM, FULL), (NONE, CUSTOM, FULL), (0, 1, 2),
    (True, False))]

#: What each state's action guarantees about the facts read right after it.
POSTCONDITION = {
    cs.CHANGE_MODES: lambda f: True,
    cs.MOVING_FRONT: lambda f: f.lift > 0,
    cs.CLAMPING_REAR: lambda f: f.rear == FULL,
    cs.CLAMPING_FRONT: lambda f: f.front == FULL,
    cs.CLAMPING_REAR_CUSTOM: lambda f: f.rear == CUSTOM,
    cs.CLAMPING_FRONT_CUSTOM: lambda f: f.front == CUSTOM,
    cs.UNCLAMPING_REAR: lambda f: f.rear == NONE,
    cs.UNCLAMPING_FRONT: lambda f: f.front == NONE,
    cs.ROTATING_REAR: lambda f: f.rear == NONE,
    cs.ROTATING_FRONT: lambda f: f.front == NONE and not f.limited,
}

#: The step name each state's action shows up as in the report's tables.
STEP = {
    cs.MOVING_FRONT: 'move front', cs.CLAMPING_REAR: 'clamp rear', cs.CLAMPING_FRONT: 'clamp front',
    cs.UNCLAMPING_REAR: 'unclamp rear partial', cs.UNCLAMPING_FRONT: 'unclamp front partial',
    cs.ROTATING_REAR: 'rotate rear', cs.ROTATING_FRONT: 'rotate front',
    cs.CLAMPING_REAR_CUSTOM: 'clamp rear custom', cs.CLAMPING_FRONT_CUSTOM: 'clamp front custom',
}

# Step lists of SPEC 8 / Tables 6.1-6.3, each step with the facts that change
# after it (the robot's answer: which clamps hold, where the rear ended up).
SIMPLE = (dict(nominal_start=True, straight=True, aligned=True), [
    ('move front', dict(lift=2)),
    ('clamp rear', dict(rear=FULL)),
    ('clamp front', dict(front=FULL)),
])
NOMINAL = (dict(nominal_start=True, straight=False, aligned=True), [
    ('move front', dict(lift=2)),
    ('clamp rear', dict(rear=FULL)),
    ('clamp front', dict(front=FULL)),
    ('unclamp rear partial', dict(rear=NONE)),
    ('rotate rear', dict(straight=True, aligned=False)),
    ('clamp rear', dict(rear=FULL)),
    ('unclamp front partial', dict(front=NONE)),
    ('rotate front', dict(aligned=True)),          # "rotate front (to 0)"
    ('clamp front', dict(front=FULL)),
])
NON_NOMINAL = (dict(nominal_start=False, straight=False, aligned=True), [
    ('clamp rear custom', dict(rear=CUSTOM)),
    ('rotate front', dict(aligned=False)),
    ('move front', dict(lift=1)),                  # first time
    ('clamp front custom', dict(front=CUSTOM)),    # first time
    ('move front', dict(lift=2)),
    ('unclamp rear partial', dict(rear=NONE)),
    ('rotate rear', dict()),                       # limited to 0.7 rad: not straight yet
    ('clamp rear custom', dict(rear=CUSTOM)),
    ('unclamp front partial', dict(front=NONE)),
    ('rotate front', dict()),
    ('clamp front custom', dict(front=CUSTOM)),
    ('unclamp rear partial', dict(rear=NONE)),
    ('rotate rear', dict(straight=True)),
    ('clamp rear', dict(rear=FULL)),
    ('unclamp front partial', dict(front=NONE)),
    ('rotate front', dict(aligned=True)),          # "rotate front (to 0)"
    ('clamp front', dict(front=FULL)),
])


# The rotation-at-limit livelock: rear nominal but not straight, rotation at its +0.7
# rad limit. The first rotate rear is clipped (no motion); the front is then
# re-set upright, which brings the rotation back, and the rear turns again.
LIMITED = (dict(nominal_start=True, straight=False, aligned=False), [
    ('move front', dict(lift=2)),
    ('clamp rear', dict(rear=FULL)),
    ('clamp front', dict(front=FULL)),
    ('unclamp rear partial', dict(rear=NONE)),
    ('rotate rear', dict(limited=True)),           # target clipped at 0.7 rad
    ('clamp rear', dict(rear=FULL)),
    ('unclamp front partial', dict(front=NONE)),
    ('rotate front', dict(limited=False)),         # eq 5.1: front upright
    ('clamp front', dict(front=FULL)),
    ('unclamp rear partial', dict(rear=NONE)),
    ('rotate rear', dict(straight=True)),
    ('clamp rear', dict(rear=FULL)),
    ('unclamp front partial', dict(front=NONE)),
    ('rotate front', dict(aligned=True)),
    ('clamp front', dict(front=FULL)),
])


def test_table_prints_every_transition():
    text = MACHINE.table()
    lines = text.splitlines()
    assert lines[0].split() == ['state', 'next', 'state', 'guard']
    assert len(lines) == 1 + len(MACHINE.transitions)
    for t in MACHINE.transitions:
        assert any(t.source in line and t.target in line and t.guard.text in line for line in lines[1:])
    print(text)


def test_every_state_reachable_and_has_an_exit():
    reached, frontier = {MACHINE.initial}, [MACHINE.initial]
    while frontier:
        state = frontier.pop()
        for t in MACHINE.exits(state):
            if t.target not in reached:
                reached.add(t.target)
                frontier.append(t.target)
    assert reached == set(MACHINE.states) == set(POSTCONDITION) | {END}
    for state in MACHINE.states:
        assert state == END or MACHINE.exits(state)


@pytest.mark.parametrize('state', sorted(POSTCONDITION))
def test_at_most_one_transition_for_every_combination(state):
    for facts in ALL_FACTS:
        fired = [t.target for t in MACHINE.exits(state) if t.guard.test(facts)]
        assert len(fired) <= 1, (state, facts, fired)


@pytest.mark.parametrize('state', sorted(POSTCONDITION))
def test_exactly_one_transition_when_facts_agree_with_the_action(state):
    for facts in ALL_FACTS:
        if POSTCONDITION[state](facts):
            fired = [t.target for t in MACHINE.exits(state) if t.guard.test(facts)]
            assert len(fired) == 1, (state, facts, fired)


def test_end_only_when_clamped_straight_and_aligned():
    for t in MACHINE.transitions:
        if t.target == END:
            for facts in ALL_FACTS:
                if t.guard.test(facts):
                    assert facts.front == FULL and facts.rear == FULL
                    assert facts.straight and facts.aligned


def walk(start, steps):
    """Drive MACHINE with the facts of an experiment; return the step names taken."""
    facts = cs.Facts(front=NONE, rear=NONE, lift=0, limited=False, **start)
    state = MACHINE.next(MACHINE.initial, facts)
    taken = []
    for _, changes in steps:
        assert state != END, 'ended after %s' % taken
        taken.append(STEP[state])
        facts = facts._replace(**changes)
        state = MACHINE.next(state, facts)
    assert state == END, 'did not end after %s (in %s)' % (taken, state)
    return taken


@pytest.mark.parametrize('experiment', [SIMPLE, NOMINAL, NON_NOMINAL, LIMITED],
                         ids=['6.1', '6.2', '6.3', 'rotation at its limit'])
def test_report_step_lists(experiment):
    start, steps = experiment
    assert walk(start, steps) == [name for name, _ in steps]


def test_already_clamped_straight_ends_at_once():
    facts = cs.Facts(True, True, True, FULL, FULL, 2, False)
    assert MACHINE.next(cs.CHANGE_MODES, facts) == END


@pytest.mark.parametrize('nominal_start, expected', [
    (True, cs.CLAMPING_FRONT), (False, cs.CLAMPING_FRONT_CUSTOM)])
def test_front_clamp_after_lifting_follows_the_start(nominal_start, expected):
    # The rear is already clamped (e.g. a second goal after a cancel): a
    # nominal start clamps the front with the full guards, a non-nominal
    # start with the custom ones (Table 5.3).
    facts = cs.Facts(nominal_start, False, True, NONE, FULL, 2, False)
    assert cs.MACHINE.next(cs.MOVING_FRONT, facts) == expected


def test_next_refuses_no_or_several_transitions():
    facts = cs.Facts(True, True, True, FULL, CUSTOM, 2, False)    # no exit of clamping rear fits
    with pytest.raises(PabFailed) as info:
        MACHINE.next(cs.CLAMPING_REAR, facts)
    assert 'no transition' in str(info.value) and 'rear=custom' in str(info.value)
    twice = StateMachine('a', [Transition('a', END, ALWAYS), Transition('a', 'b', ALWAYS),
                               Transition('b', END, ALWAYS)])
    with pytest.raises(PabFailed) as info:
        twice.next('a', None)
    assert 'more than one' in str(info.value)


def test_inconsistent_machines_are_refused():
    with pytest.raises(ValueError, match='no transition out'):
        StateMachine('a', [Transition('a', 'b', ALWAYS)])
    with pytest.raises(ValueError, match='unreachable'):
        StateMachine('a', [Transition('a', END, ALWAYS), Transition('c', END, ALWAYS)])


@pytest.mark.parametrize('machine, facts, path', [
    (home.MACHINE, home.Facts(aligned=True, lifted=False),
     [home.CHANGE_MODES, home.UNCLAMPING_FRONT, home.UNCLAMPING_REAR, home.MOVING_FRONT_DOWN]),
    (home.MACHINE, home.Facts(aligned=False, lifted=False),
     [home.CHANGE_MODES, home.UNCLAMPING_FRONT, home.ALIGNING, home.UNCLAMPING_REAR, home.MOVING_FRONT_DOWN]),
    (home.MACHINE, home.Facts(aligned=True, lifted=False, along=False),
     [home.CHANGE_MODES, home.UNCLAMPING_FRONT, home.UNCLAMPING_REAR]),
    (home.MACHINE, home.Facts(aligned=True, lifted=True),
     [home.CHANGE_MODES, home.LOWERING_FRONT, home.UNCLAMPING_FRONT, home.UNCLAMPING_REAR,
      home.MOVING_FRONT_DOWN]),
    (drive.MACHINE, None, [drive.DRIVING, drive.STOPPING]),
])
def test_home_and_drive_paths(machine, facts, path):
    # Home is the report's Fig 4.9 when aligned, and aligns while the rear
    # still holds when not; a front lifted beyond a clamp's lift
    # (a turn's steer) is lowered first, and not lowered at the end while it
    # points into an opening (Bend I past a straight pipe's); Drive is linear.
    state, walked = machine.initial, []
    while state != END:
        walked.append(state)
        state = machine.next(state, facts)
    assert walked == path
