"""Every goal has a living owner: when is the node that sent the running goal gone?

The owner of a Pirate Server goal is the node that published it (the caller
id of its ActionGoal). While a goal from another node runs, the manager
pings the owner's XMLRPC server (``getPid``) every :data:`PING_PERIOD_S`;
this module decides from each ping's outcome, on a monotonic clock (s),
whether the owner is gone, and says why:

- the connection refused or reset: the process is gone, at once;
- answered by another process than the first answer's (a node restarted
  under the owner's name is not the goal's owner): gone at once;
- no answer (timeout, any other failure, a node the master does not know):
  gone once the owner has been unanswered for :data:`UNANSWERED_S`.

A goal from the manager's own node (the panel's) lives as long as the
manager: it is not pinged. No ROS here: the pinging is in
:mod:`pirate.manager.goal_owner_ros`.
"""
import collections
import socket

#: s between pings of the running goal's owner.
PING_PERIOD_S = 0.2
#: s a ping waits for its answer (connect and reply).
PING_TIMEOUT_S = 0.2
#: s unanswered after which the owner is gone: with pings every 0.2 s that
#: time out after 0.2 s, a hung owner is cancelled <= 1 s after its last answer
#: (measurements.md#owner-lost).
UNANSWERED_S = 0.8

ANSWERED, REFUSED, UNANSWERED = 'answered', 'refused', 'unanswered'
#: One ping's outcome: ``kind`` ANSWERED / REFUSED / UNANSWERED, ``pid`` of
#: the process that answered (else None), ``why`` in words (else '').
Ping = collections.namedtuple('Ping', 'kind pid why')


def pinged(owner, own_name):
    """True when the goal's owner is pinged: a node other than the manager's
    own (``own_name``). A sender without a caller id cannot be pinged."""
    return bool(owner) and owner != own_name


def answer(reply):
    """The Ping for a ``getPid`` reply ``[code, message, pid]``."""
    code, message, pid = reply
    if code != 1:
        return Ping(UNANSWERED, None, 'getPid refused: %s' % message)
    return Ping(ANSWERED, pid, '')


def failure(error, timeout_s):
    """The Ping for an exception a ping raised."""
    if isinstance(error, (ConnectionRefusedError, ConnectionResetError)):
        return Ping(REFUSED, None, 'its XMLRPC server refused the connection: the process is gone')
    if isinstance(error, socket.timeout):
        return Ping(UNANSWERED, None, 'no answer within %.2f s' % timeout_s)
    return Ping(UNANSWERED, None, 'ping failed: %s' % (error or type(error).__name__))


#: The ping of a node the master does not know (not registered, or the master silent).
UNKNOWN = Ping(UNANSWERED, None, 'not known to the master')


class OwnerWatch(object):
    """The owner of one goal, judged ping by ping (times in monotonic s)."""

    def __init__(self, owner, goal_id, since_s, unanswered_s=UNANSWERED_S):
        self.owner, self.goal_id = owner, goal_id
        self.gone = None            # why the owner is gone, once it is
        self._answered_s = since_s  # acceptance counts as the last sign of life
        self._pid = None
        self._unanswered_s = unanswered_s

    def heard(self, ping, now_s):
        """Take one ping's outcome at ``now_s``; why the owner is gone, or None while it lives."""
        if self.gone is None:
            why = self._why_gone(ping, now_s)
            if why is not None:
                self.gone = ('goal owner %s is gone (%s): goal %s cancelled into the safe hold'
                             % (self.owner, why, self.goal_id))
        return self.gone

    def _why_gone(self, ping, now_s):
        if ping.kind == REFUSED:
            return ping.why
        if ping.kind == ANSWERED:
            if self._pid is not None and ping.pid != self._pid:
                return ('its name answered from pid %s, the goal came from pid %s: restarted, '
                        'a new process is not the goal\'s owner' % (ping.pid, self._pid))
            self._pid, self._answered_s = ping.pid, now_s
            return None
        silent_s = now_s - self._answered_s
        if silent_s < self._unanswered_s:
            return None
        return 'unanswered for %.2f s (limit %.2f s): %s' % (silent_s, self._unanswered_s, ping.why)
