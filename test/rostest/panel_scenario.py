#!/usr/bin/env python3
"""Generic panel scenario: play recorded MIDI events, check the outcome.

Each test/rostest/panel_*.test holds one scenario as the ``~steps`` param
(teleop_twist_joy style): a list of one-key dicts, run in order.

  press: CH                      MIDI press + release of button CH
  midi: [CH, VALUE]              one MidiInput event
  wait_moved: {joint, min_rad, timeout_s}
                                 |angle - angle at the step| >= min_rad in time
  wait_angle: {joint, rad, tol_rad, timeout_s}
                                 the joint reads rad within tol_rad in time
  expect_still: {joints, tol_rad, for_s}
                                 none of them moves more than tol_rad for for_s
  wait_still: {joints, tol_rad, for_s, timeout_s}
                                 they come to rest: none moves more than
                                 tol_rad for for_s, within timeout_s (a robot
                                 with a body settles after a stop)
  wait_led: {button, lit, timeout_s}     the Mapper lit / cleared an LED
  expect_led_stays: {button, lit, for_s} and it does not change
  wait_log: {contains, timeout_s}        the manager told the operator
  wait_goal: {status, timeout_s}         Pirate Server goal reached a status
                                         (active, preempted, succeeded, aborted)
  wait_setpoints_zero: {elements, timeout_s}
                                 the setpoint array on the wire has 0 there
  expect_setpoints_zero: {elements, for_s}
                                 every setpoint array on the wire for for_s
                                 (at least one) has 0 there
  wait_travel: {min_mm, timeout_s}       the odometry advances min_mm in time
  expect_no_travel: {tol_mm, for_s}      it advances no more than tol_mm for for_s
  fault: TEXT                    a fault for the firmware in the loop
                                 (fil_robot's ~fault: reset, stall 2, ...)
  wait_operator: {contains, timeout_s}   the panel told the operator (the
                                         line the virtual panel shows)
  wait_result: {index, status, timeout_s, message, guard, server_state}
                                 the index-th goal result on /pirate/result
                                 (any client) has that status, and its
                                 message / a primitive's guard / the server
                                 state after it contain those texts
  other_client: {goal}           another action client sends this goal
  camera_point: {pan, tilt, ok, says}
                                 /pirate/camera/point answers ok (true or
                                 false) with a message containing says

Timeouts are wall-clock seconds (default EVENT_WAIT_S); the robot runs in simulated time (faster).
Before the first step it waits for the robot state and for the manager to
subscribe the panel topic and send its LEDs.
"""
import threading
import time
import unittest

import rospy
import rostest

import ready
from actionlib_msgs.msg import GoalStatusArray
from rosgraph_msgs.msg import Log
from std_msgs.msg import String

from pirate import names
from pirate.robot import tables
from pirate.msg import (MidiInput, MidiOutput, PirateAction, PirateActionResult, PirateGoal, RobotState,
                        SetpointArray)
from pirate.srv import CameraPoint
from pirate.supervisory.goal_client_ros import SimpleGoalClient

STATUS = {'active': 1, 'preempted': 2, 'succeeded': 3, 'aborted': 4, 'rejected': 5}
POLL_S = 0.02
#: Wall s a step waits for its event unless it says timeout_s: a wait, not a timing
#: figure (those are in bench/), generous for a busy CI machine.
EVENT_WAIT_S = 30.0
#: Where the firmware in the loop takes its faults (pirate.testing.fil_node).
FAULT_TOPIC = '/fil_robot/fault'


class PanelScenario(unittest.TestCase):

    def setUp(self):
        self.lock = threading.Lock()
        self.angles, self.leds, self.logs, self.statuses, self.setpoints = {}, {}, [], set(), None
        self.told, self.results, self.odometry, self.wire = [], [], None, []
        self.other = SimpleGoalClient(names.PIRATE_ACTION, PirateAction)
        #: What the steps hear, each from a publisher that exists from the start.
        self.ears = [rospy.Subscriber(names.OPERATOR_TOPIC, String, self._on_operator),
                     rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self._on_state),
                     rospy.Subscriber(names.MIDI_OUTPUT_TOPIC, MidiOutput, self._on_led),
                     rospy.Subscriber(names.PIRATE_ACTION + '/status', GoalStatusArray, self._on_status),
                     rospy.Subscriber(names.PIRATE_ACTION + '/result', PirateActionResult, self._on_result),
                     rospy.Subscriber(names.SETPOINT_TOPIC, SetpointArray, self._on_setpoints)]
        rospy.Subscriber('/rosout', Log, self._on_log)
        self.pub = rospy.Publisher(names.MIDI_INPUT_TOPIC, MidiInput, queue_size=100)
        self.faults = rospy.Publisher(FAULT_TOPIC, String, queue_size=5)

    # --- recorders ---------------------------------------------------------------
    def _on_state(self, msg):
        with self.lock:
            self.angles = dict(zip(msg.name, msg.position))
            self.odometry = msg.odometry

    def _on_led(self, msg):
        with self.lock:
            self.leds[msg.button] = msg.value

    def _on_log(self, msg):
        with self.lock:
            self.logs.append(msg.msg)

    def _on_status(self, msg):
        with self.lock:
            self.statuses.update(s.status for s in msg.status_list)

    def _on_result(self, msg):
        with self.lock:
            self.statuses.add(msg.status.status)
            self.results.append(msg)

    def _on_operator(self, msg):
        with self.lock:
            self.told.append(msg.data)

    def _on_setpoints(self, msg):
        with self.lock:
            self.setpoints = list(msg.data)
            self.wire.append(self.setpoints)

    # --- helpers ---------------------------------------------------------------------
    def _until(self, condition, timeout_s, what):
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline and not rospy.is_shutdown():
            with self.lock:
                if condition():
                    return
            time.sleep(POLL_S)
        with self.lock:
            self.fail('timed out after %.1f s waiting for %s' % (timeout_s, what() if callable(what) else what))

    def _during(self, condition, for_s, what):
        deadline = time.monotonic() + for_s
        while time.monotonic() < deadline and not rospy.is_shutdown():
            with self.lock:
                self.assertTrue(condition(), what() if callable(what) else what)
            time.sleep(POLL_S)

    def _send(self, channel, value):
        self.pub.publish(MidiInput(channel=int(channel), value=int(value)))

    def _deaf(self):
        return [ear.name for ear in self.ears if ear.get_num_connections() == 0]

    # --- steps -----------------------------------------------------------------------
    def step_press(self, channel):
        self._send(channel, 127)
        self._send(channel, 0)

    def step_midi(self, event):
        self._send(*event)

    def step_wait_moved(self, arg):
        joint, start = arg['joint'], None
        with self.lock:
            start = self.angles[joint]
        self._until(lambda: abs(self.angles[joint] - start) >= arg['min_rad'],
                    arg.get('timeout_s', EVENT_WAIT_S), '%s to move %.2f rad' % (joint, arg['min_rad']))

    def step_wait_angle(self, arg):
        joint = arg['joint']
        self._until(lambda: abs(self.angles[joint] - arg['rad']) <= arg['tol_rad'],
                    arg.get('timeout_s', EVENT_WAIT_S), '%s to read %.2f rad' % (joint, arg['rad']))

    def _moved(self, joints, tol_rad):
        """A callable: the joints that moved more than ``tol_rad`` (rad, with their change) since now."""
        with self.lock:
            start = {j: self.angles[j] for j in joints}
        return lambda: ['%s %+.3f' % (j, self.angles[j] - start[j]) for j in start
                        if abs(self.angles[j] - start[j]) > tol_rad]

    def step_expect_still(self, arg):
        moved = self._moved(arg['joints'], arg['tol_rad'])
        self._during(lambda: not moved(), arg['for_s'], lambda: 'joints moved: %s' % moved())

    def step_wait_still(self, arg):
        deadline = time.monotonic() + arg.get('timeout_s', EVENT_WAIT_S)
        while time.monotonic() < deadline and not rospy.is_shutdown():
            moved, quiet_until = self._moved(arg['joints'], arg['tol_rad']), time.monotonic() + arg['for_s']
            while time.monotonic() < quiet_until:
                with self.lock:
                    if moved():
                        break
                time.sleep(POLL_S)
            else:
                return
        self.fail('the robot did not come to rest within %.1f s' % arg.get('timeout_s', EVENT_WAIT_S))

    def step_wait_led(self, arg):
        self._until(lambda: self.leds.get(arg['button']) == arg['lit'], arg.get('timeout_s', EVENT_WAIT_S),
                    'LED %d %s' % (arg['button'], 'on' if arg['lit'] else 'off'))

    def step_expect_led_stays(self, arg):
        self._during(lambda: self.leds.get(arg['button'], False) == arg['lit'], arg['for_s'],
                     'LED %d changed' % arg['button'])

    def step_wait_log(self, arg):
        self._until(lambda: any(arg['contains'] in line for line in self.logs),
                    arg.get('timeout_s', EVENT_WAIT_S), 'a log containing %r' % arg['contains'])

    def step_wait_goal(self, arg):
        code = STATUS[arg['status']]
        self._until(lambda: code in self.statuses, arg.get('timeout_s', EVENT_WAIT_S),
                    lambda: 'goal status %s (seen %s)' % (arg['status'], sorted(self.statuses)))

    def step_wait_setpoints_zero(self, arg):
        indices = [tables.element(name).index for name in arg['elements']]
        self._until(lambda: self.setpoints is not None and all(self.setpoints[i] == 0 for i in indices),
                    arg.get('timeout_s', EVENT_WAIT_S), 'zero setpoints at %s' % arg['elements'])

    def step_expect_setpoints_zero(self, arg):
        indices = [tables.element(name).index for name in arg['elements']]
        with self.lock:
            start = len(self.wire)
        time.sleep(arg['for_s'])
        with self.lock:
            sent = self.wire[start:]
        self.assertTrue(sent, 'no setpoint array on the wire for %.1f s' % arg['for_s'])
        moving = [s for s in sent if any(s[i] for i in indices)]
        self.assertFalse(moving, '%d of %d setpoint arrays drive %s, first %s'
                         % (len(moving), len(sent), arg['elements'], moving[:1]))

    def step_wait_travel(self, arg):
        with self.lock:
            start = self.odometry
        self._until(lambda: abs(self.odometry - start) >= arg['min_mm'], arg.get('timeout_s', EVENT_WAIT_S),
                    lambda: 'the odometry to advance %.0f mm (%.1f mm)' % (arg['min_mm'], self.odometry - start))

    def step_expect_no_travel(self, arg):
        with self.lock:
            start = self.odometry
        self._during(lambda: abs(self.odometry - start) <= arg['tol_mm'], arg['for_s'],
                     lambda: 'the robot travelled %.1f mm' % (self.odometry - start))

    def step_fault(self, text):
        self._until(lambda: self.faults.get_num_connections() > 0, 30, 'fil_robot to listen for faults')
        self.faults.publish(String(data=text))

    def step_wait_operator(self, arg):
        self._until(lambda: any(arg['contains'] in line for line in self.told),
                    arg.get('timeout_s', EVENT_WAIT_S),
                    lambda: 'the panel to say %r (said %s)' % (arg['contains'], self.told))

    def step_wait_result(self, arg):
        index = arg['index']
        self._until(lambda: len(self.results) > index, arg.get('timeout_s', 60),
                    lambda: 'result %d (have %d)' % (index, len(self.results)))
        with self.lock:
            msg = self.results[index]
        result = msg.result
        what = 'result %d: %s' % (index, result)
        self.assertEqual(msg.status.status, STATUS[arg['status']], what)
        self.assertIn(arg.get('message', ''), result.message, what)
        self.assertIn(arg.get('server_state', ''), result.server_state, what)
        if 'guard' in arg:
            self.assertTrue(any(arg['guard'] in p.guard for p in result.primitives), what)

    def step_other_client(self, arg):
        self.assertTrue(self.other.wait_for_server(rospy.Duration(30)), 'no action server')
        spec = arg['goal']
        self.other.send_goal(PirateGoal(name=int(spec['name']), pipe_diameter=int(spec.get('pipe_diameter', 90))))

    def step_camera_point(self, arg):
        rospy.wait_for_service(names.CAMERA_POINT_SERVICE, EVENT_WAIT_S)
        said = rospy.ServiceProxy(names.CAMERA_POINT_SERVICE, CameraPoint)(arg['pan'], arg['tilt'])
        self.assertEqual((said.ok, arg['says'] in said.message), (arg['ok'], True), said.message)

    # --- the test ----------------------------------------------------------------------
    def test_scenario(self):
        steps = rospy.get_param('~steps')
        # Each subscription connects to its publisher on its own thread, and
        # rospy retries a failed connection after 1, 2, 4 ... s: on a busy
        # machine the operator's topic was still unconnected 10 s into a
        # scenario whose LEDs were (CI). A step may only listen on
        # a connected topic.
        self._until(lambda: all(ear.get_num_connections() > 0 for ear in self.ears), 60,
                    lambda: 'our subscribers to connect (unconnected: %s)' % self._deaf())
        self._until(lambda: bool(self.angles), 30, 'the robot state on %s' % names.ROBOT_STATE_TOPIC)
        self._until(lambda: self.pub.get_num_connections() > 0, 30, 'the manager to subscribe the panel')
        ready.wait_robot_connected(60)
        self._until(lambda: 42 in self.leds, 30, 'the manager to send its LEDs')
        # The panel's PAB goals reach the server only once its action client
        # has connected (before, a press is refused); the
        # manager says so in its 1 Hz diagnostics.
        ready.wait_panel_goals_connected()
        for number, step in enumerate(steps):
            (kind, arg), = step.items()
            rospy.loginfo('panel scenario step %d: %s %s', number, kind, arg)
            getattr(self, 'step_' + kind)(arg)


if __name__ == '__main__':
    rospy.init_node('panel_scenario')
    rostest.rosrun('pirate', 'panel_scenario', PanelScenario)
