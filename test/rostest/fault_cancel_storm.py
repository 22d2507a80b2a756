#!/usr/bin/env python3
"""Cancel storms log no actionlib errors, over ROS.

Cancels for goal ids the server never saw leave goal-less records in
actionlib's status list; every later cancel-*all* made actionlib log
"Attempt to get a goal id on an uninitialized ServerGoalHandle" once per
record (480 lines for 5 Stops). The panel's Stop therefore cancels only
its own goal. Every wait is on a condition with a deadline.
"""
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalID
from rosgraph_msgs.msg import Log

from pirate import names
from pirate.msg import MidiInput
from pirate.srv import ServerStatus

from ready import wait_panel_goals_connected, wait_robot_connected, wait_until

REWIND, PLAY, STOP, TRACK_RIGHT = 43, 41, 42, 59
STORM = 'uninitialized ServerGoalHandle'
RUNS = 3


class CancelStormTest(unittest.TestCase):

    def test_stops_after_ghost_cancels_log_no_actionlib_errors(self):
        rospy.init_node('cancel_storm')
        logs = []
        rospy.Subscriber('/rosout', Log, logs.append, queue_size=1000)
        cancel = rospy.Publisher(names.PIRATE_ACTION + '/cancel', GoalID, queue_size=100)
        midi = rospy.Publisher(names.MIDI_INPUT_TOPIC, MidiInput, queue_size=100)
        wait_until(lambda: cancel.get_num_connections() > 0 and midi.get_num_connections() > 0, 'subscribers')
        wait_robot_connected()
        wait_panel_goals_connected()
        status = rospy.ServiceProxy(names.SERVER_STATUS_SERVICE, ServerStatus)

        def press(channel):
            midi.publish(MidiInput(channel=channel, value=127))
            midi.publish(MidiInput(channel=channel, value=0))

        press(REWIND)
        for run in range(RUNS):
            for ghost in range(20):
                cancel.publish(GoalID(id='ghost-%d-%d' % (run, ghost)))
            press(PLAY)
            press(TRACK_RIGHT)
            wait_until(lambda: status().active, 'the PAB running (run %d)' % run)
            press(STOP)
            wait_until(lambda: not status().active, 'the PAB cancelled (run %d)' % run)
        storm = [log.msg for log in list(logs) if STORM in log.msg]
        self.assertEqual(storm, [])


if __name__ == '__main__':
    rostest.rosrun('pirate', 'fault_cancel_storm', CancelStormTest)
