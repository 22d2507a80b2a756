#!/usr/bin/env python3
"""The operator's launch on a busy machine: a Clamp Straight from the panel,
then a mission the panel confirms, pauses and resumes, then a mission the
panel stops; the robot's state is never stale.

The test is the operator at the panel (MIDI presses beside the virtual
panel's window): Rewind (PAB mode), Play, Track > (Clamp Straight); the
result succeeds and the robot's own state (the clamp classifier on
``/pirate/state``) reads both parts clamped. Then the mission ``~map``
``~points`` on ``/pirate/mission`` at level confirm: the panel's Confirm
(M 2) lets each step run, Pause (M 3) during its first Drive holds the
robot (its wheels come to rest within a robot second, then its odometry
stands for a robot second), Resume (M 4) goes on; it
succeeds, the odometry advanced ``~travel_mm`` (within ``~travel_tol_mm``)
and the robot's state reads ``~ends``. Then the way back (``~points``
reversed): Stop on the panel while its first PAB runs cancels that PAB
and the mission, no PAB runs after it and the robot stands. All along, no
``/pirate/state`` says stale and none comes later than the stale limit of
robot time after the one before, from when the stack is ready (the
simulator runs free until the manager acknowledges its first state,
doc/clock.md). Waits on conditions, never on sleeps;
timeouts are wall seconds, generous for a machine loaded to four
processes per core.
"""
import threading
import time
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from std_msgs.msg import String

import ready
from pirate import names
from pirate.msg import (MidiInput, MidiOutput, MissionAction, MissionActionFeedback, MissionGoal,
                        PirateActionFeedback, PirateActionGoal, PirateActionResult, RobotState)
from pirate.sequencer import clamp_state
from pirate.sequencer.guards import Guards, load_files
from pirate.state.assembler import STALE_AFTER_S
from pirate.supervisory.goal_client_ros import SimpleGoalClient

PLAY, STOP, REWIND, TRACK_FORWARD = 41, 42, 43, 59
CONFIRM, PAUSE, RESUME = 49, 50, 51          # the M buttons' mission jobs in PAB mode (config/nanokontrol2.yaml)
#: Robot s the robot must stand while paused, and the odometry it may drift (mm).
HELD_S, HELD_MM = 1.0, 2.0
#: Robot s a cancelled Drive has to come to rest, and the wheel speed that is rest (mm/s).
SETTLE_S, REST_MM_S = 1.0, 1.0
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
                                     queue_size=100),
                    rospy.Subscriber(names.MISSION_ACTION + '/feedback', MissionActionFeedback, cls._on_mission,
                                     queue_size=100),
                    rospy.Subscriber(names.PIRATE_ACTION + '/goal', PirateActionGoal, cls._on_pab_goal,
                                     queue_size=100),
                    rospy.Subscriber(names.PIRATE_ACTION + '/feedback', PirateActionFeedback, cls._on_pab,
                                     queue_size=100)]
        cls.mission, cls.pab_goals, cls.running_goals = None, [], set()   # PAB goal ids sent; with feedback
        cls.panel = rospy.Publisher(names.MIDI_INPUT_TOPIC, MidiInput, queue_size=10)
        ready.wait_until(lambda: all(ear.get_num_connections() for ear in cls.ears),
                         'our subscribers to connect', START_S)
        ready.wait_robot_connected(START_S)
        ready.wait_until(lambda: cls.panel.get_num_connections(), 'the Mapper to hear our panel', START_S)
        ready.wait_until(lambda: PLAY in cls.leds, 'the Mapper to send its LEDs', START_S)
        ready.wait_panel_goals_connected(START_S)
        with cls.cond:
            cls.gaps = []           # lockstep starts at the manager's first state: judge from its readiness

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
    def _on_mission(cls, msg):
        with cls.cond:
            cls.mission = msg.feedback
            cls.cond.notify_all()

    @classmethod
    def _on_pab_goal(cls, msg):
        with cls.cond:
            cls.pab_goals.append(msg.goal_id.id)
            cls.cond.notify_all()

    @classmethod
    def _on_pab(cls, msg):
        with cls.cond:
            cls.running_goals.add(msg.status.goal_id.id)
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

    def send_mission(self, points, level):
        """Send a mission of ``points`` at ``level``: its client and an Event set when it ends."""
        client = SimpleGoalClient(names.MISSION_ACTION, MissionAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(START_S)), 'no mission executive')
        ended = threading.Event()
        client.send_goal(MissionGoal(map=rospy.get_param('~map'), points=points, level=level),
                         done_cb=lambda state, result: ended.set())
        return client, ended

    def assert_stands(self, why):
        """:data:`SETTLE_S` robot s on the wheels are at rest, then the
        odometry stands for :data:`HELD_S` robot s (from the robot's own state
        stamps). Rest is judged after the settling time, not at the first
        slow state: a Drive paused as it started showed a state from before
        its wheels turned, then rolled 6 mm to a stop."""
        with self.cond:
            settle_by = self.state.header.stamp.to_sec() + SETTLE_S
        self.wait(lambda: self.state.header.stamp.to_sec() >= settle_by, PAB_S, 'the wheels to come to rest')
        self.assertLess(abs(self.state.velocity), REST_MM_S,
                        'the wheels still turned %.1f robot s %s' % (SETTLE_S, why))
        with self.cond:
            start_stamp, start_mm = self.state.header.stamp.to_sec(), self.state.odometry
        self.wait(lambda: self.state.header.stamp.to_sec() - start_stamp >= HELD_S, PAB_S, 'robot time to pass')
        self.assertLess(abs(self.odometry() - start_mm), HELD_MM, 'the robot moved ' + why)

    def test_2_a_mission_the_panel_confirms_pauses_and_resumes(self):
        start_mm = self.odometry()
        client, ended = self.send_mission(rospy.get_param('~points'), 'confirm')
        paused = resumed = False
        confirmed = set()
        deadline = time.monotonic() + MISSION_S
        while not ended.is_set():
            self.assertLess(time.monotonic(), deadline, 'the mission did not end within %.0f s' % MISSION_S)
            with self.cond:
                self.cond.wait_for(lambda: ended.is_set() or self.mission is not None, 1.0)
                fb = self.mission
            if fb is None:
                continue
            if fb.waiting_for.startswith('confirmation') and (fb.step, paused) not in confirmed:
                confirmed.add((fb.step, paused))
                self.press(CONFIRM)
            elif fb.pab == 'DRIVE' and fb.state == 'running' and not paused:
                paused = True
                self.press(PAUSE)
            elif fb.waiting_for.startswith('resume') and not resumed:
                self.assert_stands('while the mission was paused')
                resumed = True
                self.press(RESUME)
            ended.wait(0.05)
        result = client.get_result()
        self.assertTrue(paused and resumed, 'the mission was not paused and resumed: %s' % result.log)
        self.assertEqual(client.get_state(), GoalStatus.SUCCEEDED, '\n'.join(result.log))
        self.assertEqual(result.status, 'succeeded', result.message)
        travel = self.odometry() - start_mm
        self.assertLess(abs(travel - rospy.get_param('~travel_mm')), rospy.get_param('~travel_tol_mm'),
                        'the robot travelled %.0f mm' % travel)
        self.assertEqual(self.sensed(), rospy.get_param('~ends'))
        self.assert_never_stale()

    def test_3_stop_on_the_panel_ends_a_mission(self):
        with self.cond:
            pab_results, pab_goals = len(self.results), len(self.pab_goals)
        client, ended = self.send_mission(list(reversed(rospy.get_param('~points'))), 'full')
        # a PAB of this mission runs: feedback of a goal sent after it (a late
        # feedback of the mission before does not count)
        self.wait(lambda: self.running_goals.intersection(self.pab_goals[pab_goals:]), MISSION_S,
                  'the way back\'s first PAB to run')
        self.press(STOP)
        self.assertTrue(ended.wait(PAB_S), 'the mission did not end after Stop')
        result = client.get_result()
        self.assertEqual(result.status, 'cancelled', result.message)
        self.wait(lambda: len(self.results) > pab_results, PAB_S, 'the running PAB to end')
        self.assertEqual(self.results[pab_results].status.status, GoalStatus.PREEMPTED,
                         self.results[pab_results].result.message)
        self.assert_stands('after Stop')
        self.assertEqual(len(self.results), pab_results + 1, 'a PAB ran after Stop')
        self.assert_never_stale()


if __name__ == '__main__':
    rostest.rosrun('pirate', 'operator_busy', OperatorBusy)
