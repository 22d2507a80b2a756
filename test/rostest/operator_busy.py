#!/usr/bin/env python3
"""The operator's launch on a busy machine: a Clamp Straight from the panel,
then a mission, both succeed, and the robot's state is never stale.

The test is the operator at the panel (MIDI presses beside the virtual
panel's window): Rewind (PAB mode), Play, Track > (Clamp Straight); the
result succeeds and the robot's own state (the clamp classifier on
``/pirate/state``) reads both parts clamped. Then the mission ``~map``
``~points`` on ``/pirate/mission``: it succeeds, the odometry advanced
``~travel_mm`` (within ``~travel_tol_mm``) and the robot's state reads
``~ends``. All along, no ``/pirate/state`` says stale and none comes later
than the stale limit of robot time after the one before. Waits on
conditions, never on sleeps; timeouts are wall seconds, generous for a
machine loaded to four processes per core.
"""
import threading
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from std_msgs.msg import String

import ready
from pirate import names
from pirate.msg import MidiInput, MidiOutput, MissionAction, MissionGoal, PirateActionResult, RobotState
from pirate.sequencer import clamp_state
from pirate.sequencer.guards import Guards, load_files
from pirate.state.assembler import STALE_AFTER_S
from pirate.supervisory.goal_client_ros import SimpleGoalClient

PLAY, REWIND, TRACK_FORWARD = 41, 43, 59
#: Wall s for the stack to come up, a PAB, a mission: waits, not timing figures.
START_S, PAB_S, MISSION_S = 90.0, 120.0, 180.0
PIPE_MM = 90


class OperatorBusy(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('operator_busy')
        cls.cond = threading.Condition()
        cls.state, cls.stale, cls.gaps, cls.leds, cls.told, cls.results = None, [], [], {}, [], []
        cls._last_stamp, cls._first_stamp, cls._fresh = None, None, False
        tables, common = load_files()
        cls.guards = Guards(tables[PIPE_MM], common)
        cls.ears = [rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, cls._on_state, queue_size=1000),
                    rospy.Subscriber(names.MIDI_OUTPUT_TOPIC, MidiOutput, cls._on_led, queue_size=100),
                    rospy.Subscriber(names.OPERATOR_TOPIC, String, cls._on_told, queue_size=100),
                    rospy.Subscriber(names.PIRATE_ACTION + '/result', PirateActionResult, cls._on_result,
                                     queue_size=100)]
        cls.panel = rospy.Publisher(names.MIDI_INPUT_TOPIC, MidiInput, queue_size=10)
        ready.wait_until(lambda: all(ear.get_num_connections() for ear in cls.ears),
                         'our subscribers to connect', START_S)
        ready.wait_robot_connected(START_S)
        ready.wait_until(lambda: cls.panel.get_num_connections(), 'the Mapper to hear our panel', START_S)
        ready.wait_until(lambda: PLAY in cls.leds, 'the Mapper to send its LEDs', START_S)
        ready.wait_panel_goals_connected(START_S)

    # --- recorders ---------------------------------------------------------------
    @classmethod
    def _on_state(cls, msg):
        with cls.cond:
            stamp = msg.header.stamp.to_sec()
            if msg.stale:
                cls.stale.append('at %.2f s (robot time; first state %.2f s, %s fresh before): silent boards %s'
                                 % (stamp, cls._first_stamp if cls._first_stamp is not None else stamp,
                                    'one' if cls._fresh else 'none', list(bytearray(msg.silent_boards))))
            else:
                cls._fresh = True
            if cls._first_stamp is None:
                cls._first_stamp = stamp
            if cls._last_stamp is not None and stamp - cls._last_stamp > STALE_AFTER_S:
                cls.gaps.append('%.2f s after %.2f s' % (stamp - cls._last_stamp, cls._last_stamp))
            cls._last_stamp, cls.state = stamp, msg
            cls.cond.notify_all()

    @classmethod
    def _on_led(cls, msg):
        with cls.cond:
            cls.leds[msg.button] = msg.value
            cls.cond.notify_all()

    @classmethod
    def _on_told(cls, msg):
        with cls.cond:
            cls.told.append(msg.data)

    @classmethod
    def _on_result(cls, msg):
        with cls.cond:
            cls.results.append(msg)
            cls.cond.notify_all()

    # --- helpers -----------------------------------------------------------------
    def wait(self, predicate, timeout_s, what):
        with self.cond:
            self.assertTrue(self.cond.wait_for(predicate, timeout_s), '%s; the panel said %s'
                            % (what() if callable(what) else what, self.told[-5:]))

    def press(self, channel):
        self.panel.publish(MidiInput(channel=channel, value=127))
        self.panel.publish(MidiInput(channel=channel, value=0))

    def sensed(self):
        """The server's idle state as the robot's latest state reads it (clamp classifier)."""
        with self.cond:
            msg = self.state
        angles, efforts = dict(zip(msg.name, msg.position)), dict(zip(msg.name, msg.effort))
        return clamp_state.idle_state(clamp_state.classify(self.guards, angles, efforts, msg.orientation))

    def odometry(self):
        with self.cond:
            return self.state.odometry

    def assert_never_stale(self):
        with self.cond:
            self.assertEqual(self.stale, [], 'the robot state went stale')
            self.assertEqual(self.gaps, [], 'the robot state was late by more than %.1f s' % STALE_AFTER_S)

    # --- the test ----------------------------------------------------------------
    def test_1_clamp_straight_from_the_panel(self):
        self.press(REWIND)                          # PAB mode, then Play: the panel lets goals move the robot
        self.wait(lambda: self.leds.get(REWIND), START_S, 'PAB mode')
        self.press(PLAY)
        self.wait(lambda: self.leds.get(PLAY), START_S, 'playing')
        self.press(TRACK_FORWARD)
        self.wait(lambda: self.results, PAB_S, 'the Clamp Straight result')
        result = self.results[0]
        self.assertEqual(result.status.status, GoalStatus.SUCCEEDED, result.result.message)
        self.assertEqual(result.result.server_state, clamp_state.IDLE_CLAMPED, result.result.message)
        self.assertEqual(self.sensed(), clamp_state.IDLE_CLAMPED)
        self.assert_never_stale()

    def test_2_a_mission_from_the_clamped_robot(self):
        client = SimpleGoalClient(names.MISSION_ACTION, MissionAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(START_S)), 'no mission executive')
        ended = threading.Event()
        start_mm = self.odometry()
        client.send_goal(MissionGoal(map=rospy.get_param('~map'), points=rospy.get_param('~points')),
                         done_cb=lambda state, result: ended.set())
        self.assertTrue(ended.wait(MISSION_S), 'the mission did not end within %.0f s' % MISSION_S)
        result = client.get_result()
        self.assertEqual(client.get_state(), GoalStatus.SUCCEEDED, '\n'.join(result.log))
        self.assertEqual(result.status, 'succeeded', result.message)
        travel = self.odometry() - start_mm
        self.assertLess(abs(travel - rospy.get_param('~travel_mm')), rospy.get_param('~travel_tol_mm'),
                        'the robot travelled %.0f mm' % travel)
        self.assertEqual(self.sensed(), rospy.get_param('~ends'))
        self.assert_never_stale()


if __name__ == '__main__':
    rostest.rosrun('pirate', 'operator_busy', OperatorBusy)
