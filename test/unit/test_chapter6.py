"""chapter6.loop_passes: the one shape in which a run may differ from the
report's sequence (a re-adjust pass run a whole number of times)."""
import pytest

from pirate.sim.chapter6 import (CLAMP_NOMINAL, CLAMP_NON_NOMINAL, CLAMP_SIMPLE, CUSTOM_RE_ADJUST, RE_ADJUST,
                                 loop_passes)

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
