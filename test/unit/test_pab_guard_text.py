"""Each PAB guard is written once: the text a table prints is its test.

- exhaustively over each table's facts, the printed text of every guard,
  read back by an independent parser of AND / OR / NOT / parentheses (a
  named condition read back from its printed definition), decides as the
  guard the machine runs does;
- the expression language prints precedence with parentheses, spells out
  named conditions, and refuses a guard that reads a fact the PAB does
  not have.
"""
import itertools
import re

import pytest

from pirate.sequencer.pabs import clamp, drive, home, junction_table
from pirate.sequencer.pabs.base import END, StateMachine, Transition
from pirate.sequencer.pabs.expr import (ALWAYS, all_of, any_of, definitions, equals, fact, facts_read, fields,
                                        named, not_)

FLAGS = (True, False)
CLAMPS = (clamp.NONE, clamp.CUSTOM, clamp.FULL)

JUNCTION_FACTS = [junction_table.Facts(*values)
                  for values in itertools.product(FLAGS, repeat=len(junction_table.Facts._fields))]
#: machine -> every combination of its facts.
TABLES = {
    'junction': (junction_table.MACHINES['front'], JUNCTION_FACTS),
    'junction rear first': (junction_table.MACHINES['rear'], JUNCTION_FACTS),
    'clamp': (clamp.MACHINE, [clamp.Facts(*values) for values in itertools.product(
        FLAGS, FLAGS, FLAGS, CLAMPS, CLAMPS, (0, 1, 2), FLAGS)]),
    'home': (home.MACHINE, [home.Facts(*values) for values in itertools.product(FLAGS, repeat=3)]),
    'drive': (drive.MACHINE, [None]),
}


class Reader(object):
    """Reads a printed guard back into a function of the facts: each word
    run between keywords is a fact's text or a named condition's name."""

    TOKEN = re.compile(r'\(|\)|[^()\s]+')
    KEYWORDS = ('AND', 'OR', 'NOT', '(', ')')

    def __init__(self, facts, named):
        self.facts, self.named = facts, named

    @classmethod
    def of(cls, guards):
        """A reader of the facts and named conditions ``guards`` use."""
        return cls(facts_read(guards), {name: expr.body.text for name, expr in definitions(guards).items()})

    def read(self, text):
        if text == '-':
            return lambda facts: True
        self.tokens, self.at = self.TOKEN.findall(text), 0
        decide = self._any()
        assert self.at == len(self.tokens), 'unread: %s' % self.tokens[self.at:]
        return decide

    def _peek(self):
        return self.tokens[self.at] if self.at < len(self.tokens) else None

    def _take(self):
        self.at += 1
        return self.tokens[self.at - 1]

    def _any(self):
        parts = [self._all()]
        while self._peek() == 'OR':
            self._take()
            parts.append(self._all())
        return lambda facts: any(part(facts) for part in parts)

    def _all(self):
        parts = [self._not()]
        while self._peek() == 'AND':
            self._take()
            parts.append(self._not())
        return lambda facts: all(part(facts) for part in parts)

    def _not(self):
        token = self._peek()
        if token == 'NOT':
            self._take()
            inner = self._not()
            return lambda facts: not inner(facts)
        if token == '(':
            self._take()
            inner = self._any()
            assert self._take() == ')'
            return inner
        words = []
        while self._peek() is not None and self._peek() not in self.KEYWORDS:
            words.append(self._take())
        return self._atom(' '.join(words))

    def _atom(self, text):
        if text in self.named:          # read back from its printed definition
            return Reader(self.facts, self.named).read(self.named[text])
        assert text in self.facts, 'no fact or named condition %r' % text
        return self.facts[text].test


@pytest.mark.parametrize('table', sorted(TABLES))
def test_the_printed_text_of_every_guard_decides_as_the_guard_runs(table):
    machine, every_facts = TABLES[table]
    reader = Reader.of([t.guard for t in machine.transitions])
    for t in machine.transitions:
        printed = reader.read(t.guard.text)
        for facts in every_facts:
            assert printed(facts) == t.guard.test(facts), (t.source, t.target, t.guard.text, facts)


def test_a_changed_guard_prints_differently_and_the_reader_sees_it():
    """The check above can fail: a guard whose text says one thing and whose test another is caught."""
    lead, trail = fact('lead', 'front'), fact('trail', 'rear')
    reader = Reader.of([all_of(lead, trail)])

    class Lying(object):
        text = 'front AND rear'

        @staticmethod
        def test(facts):
            return facts.lead or facts.trail

    facts = junction_table.Facts(found=False, lead=True, trail=False, straight=False, turn=False)
    assert reader.read(Lying.text)(facts) != Lying.test(facts)


OPEN, SHUT, LIT = fact('open'), fact('shut', 'door shut'), fact('lit')


@pytest.mark.parametrize('expr, text', [
    (all_of(OPEN, any_of(SHUT, LIT)), 'open AND (door shut OR lit)'),
    (any_of(OPEN, all_of(SHUT, LIT)), 'open OR (door shut AND lit)'),
    (not_(all_of(OPEN, LIT)), 'NOT (open AND lit)'),
    (not_(not_(OPEN)), 'NOT NOT open'),
    (all_of(named('bright', any_of(OPEN, LIT)), not_(SHUT)), 'bright AND NOT door shut'),
    (equals('rear', 'full'), 'rear full'),
    (ALWAYS, '-'),
])
def test_expressions_print_with_their_precedence(expr, text):
    assert expr.text == text


def test_named_conditions_are_spelled_out_once_inner_ones_too():
    bright = named('bright', any_of(OPEN, LIT))
    day = named('day', all_of(bright, not_(SHUT)))
    found = definitions([all_of(day, OPEN), not_(bright)])
    assert list(found) == ['day', 'bright']
    assert found['day'].body.text == 'bright AND NOT door shut'
    assert fields(day) == {'open', 'lit', 'shut'}


def test_a_guard_reading_a_fact_the_pab_has_not_is_refused():
    with pytest.raises(ValueError, match='reads lit, which the facts do not have'):
        StateMachine('a', [Transition('a', END, all_of(fact('turn'), LIT))], facts=junction_table.Facts)


def test_and_or_need_two_operands():
    with pytest.raises(ValueError, match='at least two'):
        all_of(OPEN)
