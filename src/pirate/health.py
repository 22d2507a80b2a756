"""Health reports for diagnostic_updater, computed without ROS.

Every node reports through ``diagnostic_updater`` (REP 107), gathered by
the aggregator (config/diagnostics.yaml) for rqt_robot_monitor. What each
status says is decided here, purely, so it is unit-tested: the nodes only
pass the report on with :func:`fill`.
"""
import collections
import math

#: diagnostic_msgs/DiagnosticStatus levels.
OK, WARN, ERROR = 0, 1, 2

#: One status: level, one-line message, and (key, value) details.
Report = collections.namedtuple('Report', 'level message values')


def fill(stat, report):
    """Copy ``report`` into a diagnostic_updater DiagnosticStatusWrapper; return it."""
    stat.summary(report.level, report.message)
    for key, value in report.values:
        stat.add(key, str(value))
    return stat


def robot_state(age_s, timeout_s):
    """Freshness of the robot state the Pirate Server works with.

    ``age_s``: wall seconds since the newest state (inf before the first);
    older than ``timeout_s`` a running goal aborts, so that is an error.
    """
    values = [('age_s', '%.3f' % age_s), ('timeout_s', timeout_s)]
    if math.isinf(age_s):
        return Report(ERROR, 'no robot state yet (robot connected? state node running?)', values)
    if age_s > timeout_s:
        return Report(ERROR, 'robot state %.2f s old (limit %.2f s): goals are refused' % (age_s, timeout_s),
                      values)
    return Report(OK, 'fresh (%.2f s old)' % age_s, values)


def server(status, active, primitive, cancelled, pipe_diameter):
    """The Pirate Server: its state (idle from the robot, or the running PAB)."""
    values = [('state', status), ('running PAB', active or '-'), ('primitive', primitive or '-'),
              ('cancelled', cancelled), ('pipe_diameter_mm', pipe_diameter)]
    if status.startswith('Idle ('):
        return Report(WARN, status, values)
    return Report(OK, status if not active else '%s: %s' % (status, primitive or 'between primitives'),
                  values)


def panel_device(connected, wanted, name):
    """The MIDI panel a driver node serves."""
    values = [('device asked', wanted or '(first panel)'), ('device', name or '-')]
    if connected:
        return Report(OK, 'panel connected: %s' % name, values)
    return Report(ERROR, 'panel %s not connected: plug it in (rosrun pirate midi_devices lists them)'
                  % (wanted or ''), values)


def panel_goals(connected):
    """Whether a PAB goal pressed on the panel reaches the Pirate Server:
    ``connected`` True / False, None without a panel in this manager."""
    if connected is None:
        return Report(OK, 'no panel in this manager (panel:=false)', [('connected', '-')])
    if connected:
        return Report(OK, 'connected to the Pirate Server', [('connected', True)])
    return Report(WARN, 'not connected to the Pirate Server yet: a PAB pressed now is refused (press again)',
                  [('connected', False)])


def command_writers(rogues, owner):
    """Who writes the command topics: only ``owner`` may.

    ``rogues``: (topic, sender) pairs heard lately from anyone else."""
    values = [('owner', owner)] + [(topic, sender) for topic, sender in rogues]
    if rogues:
        return Report(ERROR, 'second writer on the command topics: %s (only %s may command the robot); '
                      'goal cancelled, robot held and stopped'
                      % (', '.join('%s on %s' % (sender, topic) for topic, sender in rogues), owner), values)
    return Report(OK, 'only %s writes the command topics' % owner, values)


def goal_owner(owner, lost):
    """The node that sent the running goal (pinged while it runs), and why the
    last goal's owner was lost (None: it was not), until the next goal."""
    values = [('owner', owner or '-')]
    if lost:
        return Report(ERROR, lost, values)
    if owner:
        return Report(OK, 'the running goal\'s owner %s answers' % owner, values)
    return Report(OK, 'no goal from another node running', values)


def small_states(stale, reason, age_s, boards, loss=None):
    """The Small State stream as the state node sees it: every board fresh,
    or stale with the reason (the silent boards named). ``loss``: board ->
    fraction of its recent replies lost, shown per board."""
    values = [('age_s', '%.3f' % age_s), ('boards', boards)]
    values += [('board %d loss' % board, '%.1f %%' % (100.0 * rate)) for board, rate in sorted((loss or {}).items())]
    if math.isinf(age_s):
        return Report(ERROR, 'no Small State yet (robot end running? serial link up?)', values)
    if stale:
        return Report(ERROR, '%s: the state is stale, goals are refused' % reason, values)
    return Report(OK, 'all %d boards fresh' % boards, values)
