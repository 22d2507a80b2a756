#!/usr/bin/env python3
"""rostest: the simulated robot runs in lockstep with the stack (doc/clock.md).

1. Once the manager acknowledges the states it takes in, while a consumer
   is held (pirate_state stopped with SIGSTOP, the fault a loaded laptop
   makes), simulated time advances at most one Mega cycle
   (this test allows two: its own view of /clock may lag by one):
   the simulator waits for the manager's acknowledgement (the launch sets
   its wall bound far above the hold, so only the lockstep can hold it).
   Continued, the clock runs on.
2. A Clamp Straight during which pirate_state and then the manager are each
   held for ``HOLD_S`` wall seconds - at ~rate 4, sixteen times the feedback
   timeout of robot time - succeeds: a starved consumer is late, not
   silent, on simulated time.
The hold's length is the fault, not a synchronisation: the checks hold for
any length, on any machine load.
"""
import os
import signal
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Time

from pirate import names
from pirate.msg import PirateGoal
from seq_experiment import SequencerTest

HOLD_S = 1.2            # wall s a consumer is held
#: sim s the clock may move while held: the cycle the simulator may finish,
#: and one more for this test's own view of /clock lagging. Unlocked, the
#: hold is 4.8 sim s at rate 4.
HELD_MAX_S = 0.2 + 1e-6


def _pid(node):
    return xmlrpc.client.ServerProxy(rosgraph.Master('/test').lookupNode(node)).getPid('/test')[2]


class Held(object):
    """``node``'s process stopped (SIGSTOP) inside the block, continued after."""

    def __init__(self, node):
        self.pid = _pid(node)

    def __enter__(self):
        os.kill(self.pid, signal.SIGSTOP)
        return self

    def __exit__(self, *_exc):
        os.kill(self.pid, signal.SIGCONT)


class SimLockstepTest(SequencerTest):
    """The simulator waits for the stack; the stack's watchdogs see no silence."""

    @classmethod
    def setUpClass(cls):
        super(SimLockstepTest, cls).setUpClass()
        cls.clock_lock = threading.Lock()
        cls.clock_s, cls.acknowledged_s = None, None
        rospy.Subscriber('/clock', Clock, cls._on_clock, queue_size=1)   # the newest only
        rospy.Subscriber(names.LOCKSTEP_TOPIC, Time, cls._on_acknowledged, queue_size=1)
        # The simulator waits for the stack only once the stack acknowledges its
        # cycles (before, nobody may be listening): the manager must have taken
        # a state in, and the simulator stepped a few cycles since, before a hold.
        cls._wait(lambda: cls.acknowledged_s is not None, 'the manager acknowledging a state', 30.0)
        first = cls.acknowledged_s
        cls._wait(lambda: (cls._clock() or 0.0) >= first + 0.3, '/clock 0.3 s past the first acknowledgement', 30.0)

    @classmethod
    def _on_clock(cls, msg):
        with cls.clock_lock:
            cls.clock_s = msg.clock.to_sec()

    @classmethod
    def _on_acknowledged(cls, msg):
        with cls.clock_lock:
            cls.acknowledged_s = msg.data.to_sec()

    @classmethod
    def _clock(cls):
        with cls.clock_lock:
            return cls.clock_s

    def test_scenario(self):
        self._a_held_consumer_holds_simulated_time()
        self._a_starved_stack_gets_no_false_feedback_timeout()

    def _a_held_consumer_holds_simulated_time(self):
        with Held('/pirate_state'):
            start = self._clock()
            time.sleep(HOLD_S)          # the hold itself (the fault), not a synchronisation
            held = self._clock() - start
        rospy.loginfo('sim_lockstep: %.2f sim s passed in %.1f wall s with pirate_state held', held, HOLD_S)
        self.assertLessEqual(held, HELD_MAX_S,
                             'the simulator ran %.2f s on while the stack was held' % held)
        after = self._clock()
        self._wait(lambda: self._clock() - after >= 1.0, 'simulated time after the hold', 30.0)

    def _a_starved_stack_gets_no_false_feedback_timeout(self):
        self._send({'name': PirateGoal.CLAMP_STRAIGHT})
        self._wait_sim(1.0)
        for node in ('/pirate_state', '/pirate_manager'):
            with Held(node):
                time.sleep(HOLD_S)      # the starvation itself (the fault)
            self._wait_sim(0.5)
        state, _result, text = self._finish()
        self.assertEqual(state, GoalStatus.SUCCEEDED, 'with the stack starved: %s' % text)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'sim_lockstep', SimLockstepTest)
