"""A Mega reset (or a re-handshake of its link) while the operator drives:
control modes and limits come back, and every setpoint stays at the safe
hold until the operator moves a control again or presses Play; a running
goal ends. The Mapper, the command arrays and the manager's RobotLink with
recording publishers, judged on the wire."""
import os

import pytest

from pirate.manager.robot_link import RobotLink
from pirate.panel import config as panel_config
from pirate.panel.mapper import ROBOT_BACK_TOLD, Mapper
from pirate.robot import commands, link_watch, safety, tables

CONFIG = os.path.join(os.path.dirname(__file__), '..', '..', 'config', 'nanokontrol2.yaml')
PRESS, RELEASE = 127, 0
PLAY = 41
SLIDER_BEND_I, SLIDER_DRIVE, S_BEND_I, S_DRIVE = 4, 7, 36, 39
WHEELS, BEND_I = tables.element('wheels').index, tables.element('bend_i').index
SMALL_STATE_S = 0.011       # nine boards per 100 ms cycle


class Wire(object):
    """The three command topics, recorded in the order they were sent."""

    def __init__(self):
        self.sent = []

    def publisher(self, topic):
        wire = self

        class Publisher(object):
            def publish(self, msg):
                wire.sent.append((topic, msg))
        return Publisher()

    def since(self, mark, topic):
        return [msg for name, msg in self.sent[mark:] if name == topic]


class Server(object):
    """The Pirate Server as RobotLink sees it: the running PAB and its cancel."""

    def __init__(self, active=None):
        self.active, self.cancelled = active, []

    def cancel(self, reason=None):
        self.cancelled.append(reason)


class NoPab(object):
    def send_goal(self, goal):
        return False, 'no server here'

    def cancel(self):
        pass

    def is_active(self):
        return False


class Robot(object):
    """The manager's command side with a panel: Small States in, arrays out."""

    def __init__(self, server=None):
        self.wire, self.logs, self.now = Wire(), [], 0.0
        self.control = commands.Control(self.wire.publisher('control'), list)
        self.setpoint = commands.Setpoint(self.wire.publisher('setpoint'), list, self.control)
        self.limit = commands.Limit(self.wire.publisher('limits'), list)
        self.server = server or Server()
        self.mapper = Mapper(panel_config.load(CONFIG), self.setpoint, self.control, self.limit, NoPab(),
                             lambda button, on: None, self.logs.append, lambda: self.now)
        self.link = RobotLink(self.setpoint, self.control, self.limit, self.server, lambda: None,
                              lambda: self.mapper, lambda text: None)

    def press(self, channel):
        self.mapper.handle(channel, PRESS)
        self.mapper.handle(channel, RELEASE)

    def run(self, seconds):
        """Small State streams for ``seconds``; the manager's 10 Hz tick sends the arrays."""
        end = self.now + seconds
        while self.now < end:
            self.now += SMALL_STATE_S
            self.link.heard(self.now)
            if int(self.now * 10) != int((self.now - SMALL_STATE_S) * 10):
                self.setpoint.tick()
                self.limit.tick()

    def reset(self, silence_s=1.0, announced=False):
        """The Mega resets: Small State stops, then streams again; with
        ``announced`` serial_node hears it announce itself in between."""
        self.now += silence_s
        if announced:
            self.link.announced()

    def drive(self, wheels=110, bend_i=110):
        """Play; wheels in velocity, Bend I in torque; both sliders pushed up."""
        self.press(PLAY)
        self.press(S_DRIVE)
        self.press(S_BEND_I)
        self.mapper.handle(SLIDER_DRIVE, wheels)
        self.mapper.handle(SLIDER_BEND_I, bend_i)


def driven(setpoints):
    return [s for s in setpoints if s[WHEELS] != 0 or s[BEND_I] != 0]


@pytest.fixture
def robot():
    robot = Robot()
    robot.run(0.5)
    robot.drive()
    robot.run(1.0)
    assert driven(robot.wire.since(0, 'setpoint')), 'the sliders did not drive'
    return robot


@pytest.mark.parametrize('silence_s,announced', [(1.0, False), (0.12, True), (1.0, True)],
                         ids=['silence', 'announced, too short to show', 'announced and silent'])
def test_a_reset_in_manual_drive_keeps_every_setpoint_at_the_hold(robot, silence_s, announced):
    robot.reset(silence_s, announced)
    back = len(robot.wire.sent)
    robot.run(6.0)
    after = robot.wire.since(back, 'setpoint')
    assert len(after) >= 55, 'the 10 Hz stream stopped: %d setpoints in 6 s' % len(after)
    assert not driven(after), 'the last manual command resumed after the reset: %s' % driven(after)[0]
    assert robot.logs.count(ROBOT_BACK_TOLD) == 1


def test_the_hold_goes_out_before_control_and_limits(robot):
    robot.reset()
    back = len(robot.wire.sent)
    robot.run(0.05)
    topics = [name for name, _ in robot.wire.sent[back:]]
    assert topics[0] == 'setpoint' and topics[-2:] == ['control', 'limits']
    control = robot.wire.since(back, 'control')[-1]
    assert control[BEND_I] == safety.MODE_CODES['pwm']          # the worm gear holds the clamp
    assert control[tables.element('wheels').index] == safety.MODE_CODES['velocity']
    assert control[tables.element('rear_module').index] == safety.COMMAND_CODES['play']


def test_a_slider_moved_after_the_reset_drives_again(robot):
    robot.reset()
    robot.run(0.5)
    robot.mapper.handle(SLIDER_DRIVE, 110)          # the value from before: not a movement
    moved = len(robot.wire.sent)
    robot.run(0.5)
    assert not driven(robot.wire.since(moved, 'setpoint'))
    robot.mapper.handle(SLIDER_DRIVE, 111)
    moved = len(robot.wire.sent)
    robot.run(0.5)
    assert all(s[WHEELS] != 0 and s[BEND_I] == 0 for s in robot.wire.since(moved, 'setpoint'))


def test_play_after_the_reset_moves_nothing_and_takes_the_sliders_again(robot):
    robot.reset()
    robot.run(0.5)
    robot.press(PLAY)
    played = len(robot.wire.sent)
    robot.run(0.5)
    assert not driven(robot.wire.since(played, 'setpoint'))
    robot.mapper.handle(SLIDER_DRIVE, 110)          # after Play a slider's value counts again
    robot.run(0.5)
    assert robot.wire.since(played, 'setpoint')[-1][WHEELS] != 0


def test_a_running_goal_ends_when_the_robot_comes_back():
    robot = Robot(Server(active='Drive'))
    robot.run(0.5)
    assert robot.server.cancelled == []
    robot.reset()
    robot.run(0.5)
    assert robot.server.cancelled == [link_watch.BACK_REASON]


def test_the_link_up_and_its_refreshes_hold_nothing():
    robot = Robot()
    robot.run(0.05)
    robot.drive()
    robot.run(3.0)
    setpoints = robot.wire.since(0, 'setpoint')
    assert len(driven(setpoints)) >= 25 and setpoints[-1][WHEELS] != 0
    assert len(robot.wire.since(0, 'limits')) > 25 and ROBOT_BACK_TOLD not in robot.logs


def test_the_first_announcement_holds_nothing():
    robot = Robot()
    assert robot.link.announced() is None
    robot.run(0.5)
    assert robot.wire.since(0, 'setpoint') == [] and ROBOT_BACK_TOLD not in robot.logs


def test_a_stall_is_no_reset_and_the_drive_goes_on(robot):
    robot.reset(silence_s=0.3)       # a stall, a late laptop: the firmware's gate re-arms
    back = len(robot.wire.sent)
    robot.run(1.0)
    assert [name for name, _ in robot.wire.sent[back:back + 2]] == ['control', 'limits']
    assert robot.wire.since(back, 'setpoint')[-1][WHEELS] != 0
    assert ROBOT_BACK_TOLD not in robot.logs
