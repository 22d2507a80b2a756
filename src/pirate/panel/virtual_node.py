"""ROS edge of the virtual panel: pygame window <-> MidiInput / MidiOutput.

Publishes a MidiInput on ``names.MIDI_INPUT_TOPIC`` for every event the
:class:`pirate.panel.virtual.VirtualPanel` produces, lights its buttons from
MidiOutput on ``names.MIDI_OUTPUT_TOPIC``, and shows the PAB state from the
Pirate Server's action feedback and result (``/pirate/feedback``,
``/pirate/result``; when no server runs it simply shows no PAB news) and
the panel's messages to the operator (refusals, results) from
``names.OPERATOR_TOPIC``, and the running mission (its map and route from
the executive's latched ``/pirate/mission/current``, a resumed mission's
too; step k of n, autonomy level, what it waits for, how it ended from the
mission action's feedback and result); a running
PAB's time left from its goal (``/pirate/goal``) and how long a PAB of its
kind typically takes (config/supervisory.yaml ``typical_s``); kept true
by pirate.panel.status (the server's own state from
``names.SERVER_STATUS_SERVICE`` after every outcome and once a second; a
late feedback never overwrites a result; nothing stale after a manager
restart), and the robot (joints, odometry, the mission's distance along the
pipe, the LEDs) from ``names.ROBOT_STATE_TOPIC``, ``names.SETPOINT_TOPIC``
and ``names.MISSION_ALONG_TOPIC``; right of the panel, each camera's newest
image (``names.CAMERA_NAMESPACES`` + ``/image_raw``, rgb8, bgr8 or mono8;
"no image for N s" once they stop). In manual mode every slider and knob
reads what it moves (the panel map's words). In PAB mode
the M row reads its mission jobs (the panel map's ``mission_buttons``).

Private params: ``~fps`` (redraw rate, default 30), ``~screenshot`` (path:
save the window there once after the first LED arrives or after 2 s, for
documentation), ``~screenshot_after`` (save it then instead: wall s after
start), ``~panel_config`` (the panel map whose PAB buttons it lists,
default config/nanokontrol2.yaml), ``~cameras`` (show the cameras' images,
default true). Headless with ``SDL_VIDEODRIVER=dummy``.
"""
import os
import threading
import time

import pygame
import rospy

from pirate import names, paths
from pirate.msg import (MidiInput, MidiOutput, MissionActionFeedback, MissionActionGoal, MissionActionResult,
                        PirateActionFeedback, PirateActionGoal, PirateActionResult, RobotState, SetpointArray)
from pirate.srv import ServerStatus
from sensor_msgs.msg import Image
from std_msgs.msg import Float64, String

from pirate.panel import config, mission_buttons, status, virtual
from pirate.robot import commands, tables
from pirate.sequencer import goals
from pirate.supervisory import durations
from pirate.sequencer.guards import load_files
from pirate.supervisory.plan_cli import load_settings

#: The panel map whose PAB buttons the panel lists (the launch's panel_config default).
PANEL_CONFIG = os.path.join(paths.CONFIG_DIR, 'nanokontrol2.yaml')
#: Wall s between two asks of the server's state (and its wait for an answer).
SERVER_ASK_S = 1.0
#: Wall s without an image after which a camera's pane says so.
IMAGE_STALE_S = 2.0
#: Wall s between two images shown per camera: the twin's rate (10 Hz).
IMAGE_EVERY_S = 0.1
#: actionlib_msgs/GoalStatus codes -> words for the operator.
_TERMINAL = {2: 'preempted', 3: 'succeeded', 4: 'aborted', 5: 'rejected', 8: 'recalled'}


class VirtualPanelNode(object):
    """Run the window loop in the main thread; ROS callbacks only queue state."""

    def __init__(self):
        self.panel = virtual.VirtualPanel()
        panel_map = config.load(rospy.get_param('~panel_config', PANEL_CONFIG))
        self.panel.pab_list = config.pab_buttons(panel_map)
        self.panel.mission_labels = mission_buttons.labels(panel_map.mission_buttons)
        self.panel.manual_labels = status.control_labels(panel_map)
        self.status = status.PanelStatus()
        self._typical_s = load_settings()[0]['typical_s']
        self._drive_speed = load_files()[1]['drive']['default_speed']   # a Drive goal's speed 0 (mm/s)
        self._mission = ''          # the running mission's map and route (from its goal)
        self._along_mm = None       # the mission's estimate along the pipe
        self._leds = {}             # 'front' / 'rear' LED setpoint counts
        self._asked = threading.Event()
        self._lock = threading.Lock()
        self._pub = rospy.Publisher(names.MIDI_INPUT_TOPIC, MidiInput, queue_size=200)
        rospy.Subscriber(names.MIDI_OUTPUT_TOPIC, MidiOutput, self._on_led, queue_size=200)
        rospy.Subscriber(names.PIRATE_ACTION + '/goal', PirateActionGoal, self._on_goal, queue_size=10)
        rospy.Subscriber(names.PIRATE_ACTION + '/feedback', PirateActionFeedback,
                         self._on_feedback, queue_size=10)
        rospy.Subscriber(names.PIRATE_ACTION + '/result', PirateActionResult,
                         self._on_result, queue_size=10)
        rospy.Subscriber(names.OPERATOR_TOPIC, String, self._on_operator, queue_size=10)
        rospy.Subscriber(names.MISSION_CURRENT_TOPIC, MissionActionGoal, self._on_mission_goal, queue_size=10)
        rospy.Subscriber(names.MISSION_ACTION + '/feedback', MissionActionFeedback,
                         self._on_mission, queue_size=10)
        rospy.Subscriber(names.MISSION_ACTION + '/result', MissionActionResult,
                         self._on_mission_result, queue_size=10)
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self._on_state, queue_size=1)
        rospy.Subscriber(names.SETPOINT_TOPIC, SetpointArray, self._on_setpoints, queue_size=1)
        rospy.Subscriber(names.MISSION_ALONG_TOPIC, Float64, self._on_along, queue_size=1)
        self._images, self._image_at = {}, {}   # camera -> its newest image not shown yet; wall s it came
        self._shown_at = {}         # camera -> wall s its pane was last converted
        if rospy.get_param('~cameras', True):
            for camera in virtual.CAMERAS:
                rospy.Subscriber(names.CAMERA_NAMESPACES[camera] + '/image_raw', Image, self._on_image, camera,
                                 queue_size=1, buff_size=2 ** 20)
        threading.Thread(target=self._ask_server, name='server_status', daemon=True).start()
        self._fps = float(rospy.get_param('~fps', 30.0))
        self._screenshot = rospy.get_param('~screenshot', '')
        self._screenshot_after = rospy.get_param('~screenshot_after', None)

    def _on_led(self, msg):
        with self._lock:
            self.panel.set_led(msg.button, msg.value)

    def _on_goal(self, msg):
        pab = goals.CODE_NAMES.get(msg.goal.name, '')
        typical = durations.typical_s(pab, msg.goal.distance, msg.goal.speed or self._drive_speed,
                                      self._typical_s)
        with self._lock:
            self.status.goal(msg.goal_id.id, typical, rospy.get_time())

    def _on_feedback(self, msg):
        with self._lock:
            self.status.feedback(msg.status.goal_id.id, feedback_text(msg.feedback))
            self._show()

    def _on_operator(self, msg):
        with self._lock:
            self.panel.operator_text = msg.data

    def _on_mission_goal(self, msg):
        with self._lock:
            self._mission = mission_name(msg.goal)

    def _on_mission(self, msg):
        with self._lock:
            self.status.mission_line(mission_text(msg.feedback, self._mission))
            self._show()

    def _on_mission_result(self, msg):
        with self._lock:
            self.status.mission_line('%s: %s' % (msg.result.status or 'ended', msg.result.message))
            self._show()

    def _on_result(self, msg):
        outcome = _TERMINAL.get(msg.status.status, 'ended')
        with self._lock:
            self.status.result(msg.status.goal_id.id, 'PAB %s: %s' % (outcome, msg.result.message))
            self._show()
        self._asked.set()       # the server's own state, now

    def _on_state(self, msg):
        with self._lock:
            self.panel.robot_text = status.robot_line(dict(zip(msg.name, msg.position)), msg.odometry,
                                                      self._along_mm, self._leds)

    def _on_setpoints(self, msg):
        with self._lock:
            self._leds = {led.split('_')[0]: msg.data[tables.element(led).index] for led in commands.LEDS}

    def _on_image(self, msg, camera):
        with self._lock:
            self._images[camera] = msg
            self._image_at[camera] = time.monotonic()

    def _show_images(self):
        """Each camera's newest image, converted here at most every
        IMAGE_EVERY_S (a grabber may send 30 large frames a second); a camera
        whose images stopped says so rather than show its last one."""
        now = time.monotonic()
        for camera, at in self._image_at.items():
            if camera in self._images and now - self._shown_at.get(camera, -IMAGE_EVERY_S) >= IMAGE_EVERY_S:
                msg = self._images.pop(camera)
                try:
                    self.panel.cameras[camera] = virtual.camera_surface(msg.width, msg.height, msg.encoding,
                                                                        msg.step, msg.data)
                except ValueError as bad:
                    self.panel.cameras[camera] = str(bad)
                self._shown_at[camera] = now
            if now - at > IMAGE_STALE_S:
                self.panel.cameras[camera] = 'no image for %.0f s' % (now - at)

    def _on_along(self, msg):
        with self._lock:
            self._along_mm = msg.data

    def _show(self):
        self.panel.pab_text = self.status.pab_line(rospy.get_time())
        self.panel.mission_text = self.status.mission

    def _ask_server(self):
        """Ask /pirate/server_status after every outcome and about once a second (wall)."""
        proxy = rospy.ServiceProxy(names.SERVER_STATUS_SERVICE, ServerStatus)
        while not rospy.is_shutdown():
            try:
                proxy.wait_for_service(SERVER_ASK_S)
                answer = proxy()
                said = (answer.active, ('%s %s' % (answer.server_state, answer.pab_state)).strip())
            except (rospy.ROSException, rospy.ServiceException):
                said = (False, None)
            with self._lock:
                self.status.server_status(*said)
                self._show()
            self._asked.wait(SERVER_ASK_S)
            self._asked.clear()

    def run(self):
        pygame.display.init()
        try:
            screen = pygame.display.set_mode((virtual.WIDTH, virtual.HEIGHT), 0, virtual.DEPTH_BITS)
        except pygame.error as err:
            rospy.logfatal('virtual panel: cannot open a window (%s); set DISPLAY, or '
                           'SDL_VIDEODRIVER=dummy to run headless', err)
            return
        pygame.display.set_caption('PIRATE panel (virtual nanoKONTROL2)')
        clock = pygame.time.Clock()
        start = time.monotonic()
        while not rospy.is_shutdown():
            for event in pygame.event.get():
                if event.type == pygame.QUIT:
                    rospy.signal_shutdown('virtual panel window closed')
                    return
                with self._lock:
                    produced = self.panel.handle_event(event)
                for channel, value in produced:
                    self._pub.publish(MidiInput(channel=channel, value=value))
            with self._lock:
                self._show_images()
                self.panel.draw(screen)
            pygame.display.flip()
            if self._screenshot and self._screenshot_due(time.monotonic() - start):
                pygame.image.save(screen, os.path.expanduser(self._screenshot))
                rospy.loginfo('virtual panel: screenshot saved to %s', self._screenshot)
                self._screenshot = ''
            clock.tick(self._fps)

    def _screenshot_due(self, running_s):
        if self._screenshot_after is not None:
            return running_s >= float(self._screenshot_after)
        return bool(self.panel.leds) or running_s > 2.0


def feedback_text(fb):
    """One status line from a Pirate feedback: the primitive with its numbers, or the server state."""
    if not fb.primitive:
        return 'Server: %s %s' % (fb.server_state, fb.pab_state)
    numbers = ''.join(' %s %.2f/%.2f' % row for row in zip(fb.guard_joints, fb.guard_values,
                                                           fb.guard_thresholds))
    timing = ' (%.1f of %.0f s)' % (fb.elapsed, fb.timeout) if fb.timeout else ''
    return 'PAB running: %s / %s / %s%s%s' % (fb.server_state, fb.pab_state, fb.primitive,
                                               numbers or ' ' + fb.guard, timing)


def mission_name(goal):
    """The mission as the operator names it: map and route ('inspection_tee_90 launch_pit -> target')."""
    return '%s %s' % (goal.map, ' -> '.join(goal.points))


def mission_text(fb, mission=''):
    """One status line from a mission feedback: which mission (``mission``,
    :func:`mission_name`), its step and option, where it is, the level and
    what it waits for."""
    waiting = ', WAITING for %s' % fb.waiting_for if fb.waiting_for else ''
    return '%sstep %d/%d %s%s at %.0f mm, level %s, about %.0f s left%s' % (
        mission + ': ' if mission else '', fb.step, fb.steps, fb.pab, ' ' + fb.option if fb.option else '',
        fb.along_mm, fb.level, fb.time_left_s, waiting)


def main():
    rospy.init_node('virtual_panel')
    VirtualPanelNode().run()
