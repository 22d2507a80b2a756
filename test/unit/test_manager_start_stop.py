"""pirate_manager stopped (SIGINT, SIGTERM) while it starts: its action
server is up before the end of its start-up, so a stop can come before the
handler that sends the safe hold was in place. It then ended on Python's own
KeyboardInterrupt (exit -2, no safe hold; the rostest seq_sigint beside a
busy load); a stop asked while starting is now kept and carried out once
the manager can."""
import os
import signal

import pytest

from pirate.manager import manager_node

SIGNALS = (signal.SIGINT, signal.SIGTERM)


@pytest.fixture
def no_ros(monkeypatch):
    """main() without a master: no node, no spin; the signal handlers restored after."""
    monkeypatch.setattr(manager_node.rospy, 'init_node', lambda *args, **kwargs: None)
    monkeypatch.setattr(manager_node.rospy, 'spin', lambda: None)
    handlers = {sig: signal.getsignal(sig) for sig in SIGNALS}
    yield
    for sig, handler in handlers.items():
        signal.signal(sig, handler)


@pytest.mark.parametrize('sig', SIGNALS)
def test_a_stop_asked_while_the_manager_starts_sends_the_safe_hold_once_it_can(no_ros, monkeypatch, sig):
    stopped = []

    class Starting(object):
        def __init__(self):
            os.kill(os.getpid(), sig)       # the stop comes while it starts

        def shutdown(self, *_signal):
            stopped.append('safe hold')

    monkeypatch.setattr(manager_node, 'PirateManager', Starting)
    manager_node.main()
    assert stopped == ['safe hold']
    assert signal.getsignal(sig) is not None and signal.getsignal(sig) != signal.SIG_DFL


def test_a_manager_that_started_unasked_runs_on(no_ros, monkeypatch):
    stopped = []

    class Started(object):
        def shutdown(self, *_signal):
            stopped.append('safe hold')

    monkeypatch.setattr(manager_node, 'PirateManager', Started)
    manager_node.main()
    assert stopped == []
