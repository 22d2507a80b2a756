"""The report's Chapter 6 clamp runs as primitive sequences (Tables 6.1-6.3),
and the one way a physical run may differ from them: a re-adjust pass run a
whole number of times instead of once.

The physics twin settles and slips where the real robot did not in the
report's runs (notes/issue-9.md): a clamp on a side or a custom-clamped part
rolls by a few hundredths of a rad, so the server repeats a re-adjust pass
until the roll is straight. Tests and benchmarks on the twin accept that
shape, and only that shape (:func:`loop_passes`); no ROS here.
"""

#: Table 6.1: simple clamp straight.
CLAMP_SIMPLE = ['move front', 'clamp rear', 'clamp front']
#: Table 6.2's re-adjust pass (full clamps), after the simple clamp.
RE_ADJUST = ['unclamp rear partial', 'rotate rear', 'clamp rear', 'unclamp front partial',
             'rotate front (align)', 'clamp front']
#: Table 6.2: nominal re-adjust.
CLAMP_NOMINAL = CLAMP_SIMPLE + RE_ADJUST
#: Table 6.3's re-adjust pass with custom clamps (lying on a side).
CUSTOM_RE_ADJUST = ['unclamp rear partial', 'rotate rear', 'clamp rear custom', 'unclamp front partial',
                    'rotate front', 'clamp front custom']
#: Table 6.3: non-nominal (custom clamps, one custom pass, then Table 6.2's pass).
CLAMP_NON_NOMINAL = (['clamp rear custom', 'rotate front', 'move front first', 'clamp front custom first',
                      'move front later'] + CUSTOM_RE_ADJUST + RE_ADJUST)


def loop_passes(executed, report, loop):
    """n when ``executed`` is ``report`` with its first ``loop`` pass run n
    times (n >= 0) instead of once; None when it is anything else."""
    executed, report, loop = list(executed), list(report), list(loop)
    start = next(i for i in range(len(report)) if report[i:i + len(loop)] == loop)
    head, tail = report[:start], report[start + len(loop):]
    body = executed[len(head):len(executed) - len(tail)]
    passes, rest = divmod(len(body), len(loop))
    if len(executed) < len(head) + len(tail) or rest or head + body + tail != executed or body != loop * passes:
        return None
    return passes
