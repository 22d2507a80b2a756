"""The panel's client sends a goal only once its action topics reach the Pirate Server.

actionlib drops a goal published before the client's goal topic is
connected to the server, without a word: in CI a panel press 30 ms after
pirate_manager started was logged "sent" and never ran
(panel_clamp_cancel.test, goal status never seen). The client's
``connect`` waits for the server once, off the press path; a press before
that is refused at once with the reason.
"""
import threading
from types import SimpleNamespace

from pirate.panel.config import Goal
from pirate.manager import manager_node

CLAMP = Goal(name=0, distance=0.0, speed=0.0, option=0)


class ActionClient(object):
    """An actionlib.ActionClient whose server is connected (or not)."""

    def __init__(self, connected):
        self.connected, self.sent, self.waited = connected, [], []

    def wait_for_server(self, timeout=None):
        self.waited.append(timeout)
        return self.connected

    def send_goal(self, goal, transition_cb=None):
        self.sent.append(goal)
        return object()


def client(connected, active=''):
    """A PabClient whose ``connect`` has returned (the server reached, or shutdown first)."""
    pab = manager_node.PabClient.__new__(manager_node.PabClient)
    pab._server, pab._pipe_diameter = SimpleNamespace(active=active), 90
    pab._client, pab._handle, pab.connected = ActionClient(connected), None, threading.Event()
    pab.connect()
    return pab


def test_a_goal_is_sent_once_connected_without_waiting_in_the_press():
    pab = client(connected=True)
    assert pab.send_goal(CLAMP) == (True, '')
    assert [g.pipe_diameter for g in pab._client.sent] == [90]
    assert pab._client.waited == [None]          # the one wait, in connect, none per press


def test_a_goal_the_server_cannot_receive_yet_is_refused_not_dropped():
    pab = client(connected=False)
    accepted, reason = pab.send_goal(CLAMP)
    assert not accepted
    assert 'not connected to the Pirate Server' in reason and 'nothing was sent' in reason
    assert pab._client.sent == []


def test_a_running_pab_is_named_before_any_wait():
    pab = client(connected=True, active='Clamp Straight')
    assert pab.send_goal(CLAMP) == (False, 'a PAB is running (Clamp Straight)')
    assert pab._client.sent == []
