"""The ROS edge of :mod:`pirate.manager.goal_owner`: find and ping a goal's owner.

One :class:`OwnerMonitor` thread in pirate_manager pings the owner of the
running goal while a goal from another node runs. The owner's XMLRPC URI
is looked up on the master when the goal is accepted (again at each ping
until the master names it) and kept: a node restarted under the same name
has another URI, and the old one refuses.
Every XMLRPC call has its own socket timeout (a Transport of its own; the
process-wide ``socket.setdefaulttimeout`` would change rospy's sockets too).
"""
import threading
import time
import xmlrpc.client

import rosgraph

from pirate.manager import goal_owner

#: s the master may take to name the owner's URI.
LOOKUP_TIMEOUT_S = 0.5


class _Timed(xmlrpc.client.Transport):
    """An XMLRPC transport whose connections time out after ``timeout_s``."""

    def __init__(self, timeout_s):
        xmlrpc.client.Transport.__init__(self)
        self._timeout_s = timeout_s

    def make_connection(self, host):
        connection = xmlrpc.client.Transport.make_connection(self, host)
        connection.timeout = self._timeout_s
        return connection


def owner_of(handle):
    """The caller id of the node that published ``handle``'s goal (actionlib's
    ServerGoalHandle keeps the ActionGoal message in ``goal``), or None."""
    header = getattr(getattr(handle, 'goal', None), '_connection_header', None) or {}
    return header.get('callerid')


def lookup_node(own_name, node):
    """``node``'s XMLRPC URI from the master, or None when it does not name one in time."""
    master = rosgraph.Master(own_name)
    master.handle = xmlrpc.client.ServerProxy(master.master_uri, transport=_Timed(LOOKUP_TIMEOUT_S))
    try:
        return master.lookupNode(node)
    except Exception:  # pylint: disable=broad-except; not named (unknown, the master silent): pinged as unknown
        return None


def ping_node(own_name, uri, timeout_s=goal_owner.PING_TIMEOUT_S):
    """Ask the node at ``uri`` for its pid: a :data:`goal_owner.Ping`."""
    proxy = xmlrpc.client.ServerProxy(uri, transport=_Timed(timeout_s))
    try:
        return goal_owner.answer(proxy.getPid(own_name))
    except Exception as error:  # pylint: disable=broad-except; every failure is an unanswered ping
        return goal_owner.failure(error, timeout_s)
    finally:
        proxy('close')()


class _Goal(object):
    """The running goal's handle, its owner's watch and URI (None until the master names it)."""

    def __init__(self, handle, watch):
        self.handle, self.watch, self.uri = handle, watch, None


class OwnerMonitor(object):
    """Pings the owner of the running goal; ``on_gone(handle, reason)`` once it is gone.

    :meth:`watch` at acceptance, :meth:`release` when the goal's handle is
    terminal, :meth:`run` in one thread. ``lookup(own_name, node)``,
    ``ping(own_name, uri)`` and ``clock`` are the ROS calls and time.monotonic
    unless a test passes others."""

    def __init__(self, own_name, on_gone, lookup=lookup_node, ping=ping_node, clock=time.monotonic):
        self.own_name, self._on_gone = own_name, on_gone
        self._lookup, self._ping, self._clock = lookup, ping, clock
        self._changed = threading.Condition()
        self._goal = None
        self.lost = None        # why the last goal's owner was lost, until the next goal

    @property
    def owner(self):
        """The running goal's pinged owner, or None."""
        goal = self._goal
        return goal.watch.owner if goal is not None else None

    def watch(self, handle):
        """A goal was accepted: ping its owner from now on, unless it is this node."""
        owner = owner_of(handle)
        with self._changed:
            self.lost = None
            self._goal = None
            if goal_owner.pinged(owner, self.own_name):
                self._goal = _Goal(handle, goal_owner.OwnerWatch(owner, handle.get_goal_id().id, self._clock()))
            self._changed.notify()

    def release(self, handle):
        """``handle``'s goal ended: its owner is no longer pinged."""
        with self._changed:
            if self._goal is not None and self._goal.handle is handle:
                self._goal = None

    def run(self, is_shutdown):
        """Ping the running goal's owner every PING_PERIOD_S until ``is_shutdown()``."""
        while not is_shutdown():
            with self._changed:
                if self._goal is None:
                    self._changed.wait(0.5)
                goal = self._goal
            if goal is not None:
                self.check(goal)
                with self._changed:
                    self._changed.wait(goal_owner.PING_PERIOD_S)

    def check(self, goal):
        """Ping ``goal``'s owner once; cancel through ``on_gone`` when it is gone."""
        if goal.uri is None:
            goal.uri = self._lookup(self.own_name, goal.watch.owner)
        ping = self._ping(self.own_name, goal.uri) if goal.uri else goal_owner.UNKNOWN
        reason = goal.watch.heard(ping, self._clock())
        if reason is None:
            return
        with self._changed:
            if self._goal is not goal:
                return          # the goal ended meanwhile
            self._goal, self.lost = None, reason
        self._on_gone(goal.handle, reason)
