"""The Pirate Server's tunables (cfg/Sequencer.cfg), checked and applied. Pure.

The report found the straight tolerance of Clamp Straight too strict
(section 7.2); timeouts depend on the robot. Operators change them with
dynamic_reconfigure; the server applies a change only between goals, so a
running PAB never sees its regions or timeouts move under it.
"""

#: The tunables and where they live: config/sequencer.yaml (common) or the feed.
NAMES = ('straight_low', 'straight_high', 'primitive_timeout', 'feedback_timeout')


def current(common, feed):
    """The tunables as they are now: {name: value}."""
    low, high = common['regions']['straight']
    return {'straight_low': float(low), 'straight_high': float(high),
            'primitive_timeout': float(common['primitive_timeout']),
            'feedback_timeout': float(feed.feedback_timeout)}


def problem(values, common):
    """Why ``values`` cannot be applied, or None."""
    low, high = values['straight_low'], values['straight_high']
    nominal_low, nominal_high = common['regions']['nominal']
    if not low < high:
        return 'straight_low %.3f must be below straight_high %.3f' % (low, high)
    if low < nominal_low or high > nominal_high:
        return ('the straight region [%.3f, %.3f] must lie inside the nominal one [%.2f, %.2f] '
                '(Table 5.4)' % (low, high, nominal_low, nominal_high))
    if values['primitive_timeout'] <= 0 or values['feedback_timeout'] <= 0:
        return 'timeouts must be above 0 s'
    return None


def apply(values, common, feed):
    """Write checked ``values`` into the common settings and the feed."""
    common['regions']['straight'] = [values['straight_low'], values['straight_high']]
    common['primitive_timeout'] = values['primitive_timeout']
    feed.feedback_timeout = values['feedback_timeout']
