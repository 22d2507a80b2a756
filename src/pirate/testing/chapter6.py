"""The report's Chapter 6 clamp runs as primitive sequences (Tables 6.1-6.3)
and the angles they reached (Table 6.5), and the one way a physical run may differ from them: a re-adjust pass (or
each of Table 6.3's two) run a whole number of times instead of once.

The physics twin settles and slips where the real robot did not in the
report's runs: a clamp on a side or a custom-clamped part
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

#: Table 6.5 averages: primitive -> {joint: rad}.
TABLE_6_5 = {
    'clamp front': {'bend_i': -0.85, 'bend_ii': 0.42}, 'clamp rear': {'bend_iv': -0.82, 'bend_iii': 0.44},
    'unclamp front partial': {'bend_i': -0.34, 'bend_ii': 0.20},
    'unclamp rear partial': {'bend_iv': -0.33, 'bend_iii': 0.20},
    'unclamp rear': {'bend_iv': 0.06, 'bend_iii': -0.09}, 'unclamp front': {'bend_i': 0.00, 'bend_ii': 0.00},
    'clamp rear custom': {'bend_iv': -0.79, 'bend_iii': 0.43},
    'clamp front custom first': {'bend_i': -0.77, 'bend_ii': 0.34},
    'clamp front custom': {'bend_i': -0.77, 'bend_ii': 0.36},
    'move front': {'front_tilt': 0.445}, 'move front first': {'front_tilt': 0.265},
    'move front later': {'front_tilt': 0.38}, 'rotate front (align)': {'rotation': 0.01},
}


#: Any re-adjust pass of Table D.1: each clamp full or custom and the front's
#: turn eq 5.1 or the align, as the facts at that step decide ('a|b': either).
ANY_RE_ADJUST = ['unclamp rear partial', 'rotate rear', 'clamp rear custom|clamp rear', 'unclamp front partial',
                 'rotate front|rotate front (align)', 'clamp front custom|clamp front']


def _fits(steps, pattern):
    """True when ``steps`` match ``pattern`` step by step ('a|b' matches a or b)."""
    return len(steps) == len(pattern) and all(step in want.split('|') for step, want in zip(steps, pattern))


def _ends_like(executed, tail):
    """``executed`` is ``tail``, or ``tail`` cut right after a full 'clamp rear':
    Table D.1 ends there when the front is clamped and the roll is straight
    (the twin: a last pass that only had to re-adjust the rear)."""
    return executed == tail or (executed[-1:] == ['clamp rear'] and tail[:len(executed)] == executed)


def pass_counts(executed, report, loops):
    """(n_1, ...) when ``executed`` is ``report`` with each pass of ``loops``
    (patterns of passes of ``report``, in its order) run n_i >= 0 times
    instead of once, ending as :func:`_ends_like` allows; None when it is
    anything else. A pass may be followed
    by one that begins like it (Table 6.3: the custom pass, then Table
    6.2's), so every count a pass can have is tried, most first."""
    executed, report = list(executed), list(report)
    if not loops:
        return () if _ends_like(executed, report) else None
    loop = list(loops[0])
    start = next(i for i in range(len(report)) if _fits(report[i:i + len(loop)], loop))
    head, rest = report[:start], report[start + len(loop):]
    if executed[:len(head)] != head:
        return None
    body, most = executed[len(head):], 0
    while _fits(body[most * len(loop):(most + 1) * len(loop)], loop):
        most += 1
    for passes in range(most, -1, -1):
        later = pass_counts(body[passes * len(loop):], rest, loops[1:])
        if later is not None:
            return (passes,) + later
    return None


def loop_passes(executed, report, loop):
    """n when ``executed`` is ``report`` with its pass ``loop`` run n times
    (n >= 0) instead of once; None when it is anything else."""
    counts = pass_counts(executed, report, [loop])
    return None if counts is None else counts[0]
