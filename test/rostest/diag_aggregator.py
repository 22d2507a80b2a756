#!/usr/bin/env python3
"""rostest: what the nodes report through diagnostic_updater reaches the aggregator.

``~expected``: [name start, name part, message part] rows; each must appear
in one /diagnostics_agg status at level OK within the deadline.
"""
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus

DEADLINE_S = 60.0


class AggregatorTest(unittest.TestCase):

    def test_statuses_reach_the_aggregator(self):
        rospy.init_node('diag_aggregator_test')
        lock, seen = threading.Lock(), {}

        def on_agg(msg):
            with lock:
                seen.update((s.name, (s.level, s.message)) for s in msg.status)
        rospy.Subscriber('/diagnostics_agg', DiagnosticArray, on_agg)
        expected = rospy.get_param('~expected')

        def found(row):
            start, part, message = row
            return any(name.startswith(start) and part in name and message in text
                       and level == DiagnosticStatus.OK for name, (level, text) in seen.items())
        deadline = time.monotonic() + DEADLINE_S
        while time.monotonic() < deadline and not rospy.is_shutdown():
            with lock:
                if all(found(row) for row in expected):
                    return
            time.sleep(0.1)    # poll what the subscriber collected
        with lock:
            self.fail('not in /diagnostics_agg as OK: %s; seen: %s'
                      % ([r for r in expected if not found(r)], seen))


if __name__ == '__main__':
    rostest.rosrun('pirate', 'diag_aggregator', AggregatorTest)
