"""chapter6.loop_passes: the one shape in which a run may differ from the
report's sequence (a re-adjust pass run a whole number of times)."""
import pytest

from pirate.testing.chapter6 import (ANY_RE_ADJUST, CLAMP_NOMINAL, CLAMP_NON_NOMINAL, CLAMP_SIMPLE, CUSTOM_RE_ADJUST, RE_ADJUST,
                                 loop_passes, pass_counts)

CUSTOM_HEAD = CLAMP_NON_NOMINAL[:5]


@pytest.mark.parametrize('executed, report, loop, passes', [
    (CLAMP_NOMINAL, CLAMP_NOMINAL, RE_ADJUST, 1),
    (CLAMP_SIMPLE, CLAMP_NOMINAL, RE_ADJUST, 0),
    (CLAMP_SIMPLE + RE_ADJUST * 3, CLAMP_NOMINAL, RE_ADJUST, 3),
    (CLAMP_NON_NOMINAL, CLAMP_NON_NOMINAL, CUSTOM_RE_ADJUST, 1),
    (CUSTOM_HEAD + CUSTOM_RE_ADJUST * 2 + RE_ADJUST, CLAMP_NON_NOMINAL, CUSTOM_RE_ADJUST, 2),
])
def test_a_pass_run_n_times_counts_n(executed, report, loop, passes):
    assert loop_passes(executed, report, loop) == passes


@pytest.mark.parametrize('executed', [
    CLAMP_SIMPLE[:2],                                   # cut short
    CLAMP_SIMPLE + RE_ADJUST[:3],                       # half a pass
    CLAMP_SIMPLE + RE_ADJUST + ['drive'],               # something after
    ['clamp rear'] + CLAMP_SIMPLE[1:] + RE_ADJUST,      # another head
    CLAMP_SIMPLE + CUSTOM_RE_ADJUST,                    # the other pass
])
def test_anything_else_is_none(executed):
    assert loop_passes(executed, CLAMP_NOMINAL, RE_ADJUST) is None


def test_the_non_nominal_tail_must_stay():
    assert loop_passes(CUSTOM_HEAD + CUSTOM_RE_ADJUST * 2, CLAMP_NON_NOMINAL, CUSTOM_RE_ADJUST) is None


@pytest.mark.parametrize('custom, nominal', [(1, 1), (2, 1), (1, 2), (2, 2), (0, 1), (1, 0)])
def test_both_passes_of_table_6_3_counted(custom, nominal):
    executed = CUSTOM_HEAD + CUSTOM_RE_ADJUST * custom + RE_ADJUST * nominal
    assert pass_counts(executed, CLAMP_NON_NOMINAL, [CUSTOM_RE_ADJUST, RE_ADJUST]) == (custom, nominal)


def test_two_passes_in_the_wrong_order_are_none():
    executed = CUSTOM_HEAD + RE_ADJUST + CUSTOM_RE_ADJUST
    assert pass_counts(executed, CLAMP_NON_NOMINAL, [CUSTOM_RE_ADJUST, RE_ADJUST]) is None


HYBRID = ['unclamp rear partial', 'rotate rear', 'clamp rear custom', 'unclamp front partial',
          'rotate front (align)', 'clamp front']


def test_any_table_pass_then_the_report_last_pass():
    """The twin at x30: a pass with the rear custom-clamped and the front aligned
    and fully clamped (the robot turned nominal mid-pass), then Table 6.2's."""
    executed = CUSTOM_HEAD + CUSTOM_RE_ADJUST * 2 + HYBRID + RE_ADJUST
    assert pass_counts(executed, CLAMP_NON_NOMINAL, [ANY_RE_ADJUST]) == (3,)
    assert pass_counts(CLAMP_NON_NOMINAL, CLAMP_NON_NOMINAL, [ANY_RE_ADJUST]) == (1,)
    assert pass_counts(CUSTOM_HEAD + CUSTOM_RE_ADJUST * 2, CLAMP_NON_NOMINAL, [ANY_RE_ADJUST]) is None   # no last full pass
    assert pass_counts(CUSTOM_HEAD + HYBRID[:4] + RE_ADJUST, CLAMP_NON_NOMINAL, [ANY_RE_ADJUST]) is None


def test_the_table_may_end_after_the_rear_clamp():
    """seq_nonnominal_right on the twin: the last pass stopped after 'clamp rear'
    (front clamped, roll straight: Table D.1's exit from clamping rear)."""
    executed = CUSTOM_HEAD + CUSTOM_RE_ADJUST + HYBRID + RE_ADJUST[:3]
    assert pass_counts(executed, CLAMP_NON_NOMINAL, [ANY_RE_ADJUST]) == (2,)
    assert pass_counts(executed[:-1], CLAMP_NON_NOMINAL, [ANY_RE_ADJUST]) is None      # cut after rotating
