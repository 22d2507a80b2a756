"""Shared pieces of the firmware-in-the-loop rostests: waiting on a
condition, the laptop's command stream, and what the boards applied.

The laptop is either ROS publishers (our serial_node forwards them) or a
:class:`pirate.link.rosserial_python_rules.RosserialPythonRules` host fed
directly (``send(name, msg)`` stands for the ROS callback).
"""
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time

import rospkg
import rospy

from pirate import names
from pirate.msg import ControlArray, LimitArray, SetpointArray
from pirate.testing.fil import FirmwareInTheLoop, build_native_firmware
from pirate.link.rosserial_python_rules import serialise
from pirate.sim.robot_end import make_robot

SETPOINT_PAYLOAD = 2 * 13          # serialised SetpointArray: how the relay tells it apart
BOARDS = 9


def wait_for(condition, timeout, what):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return
        time.sleep(0.01)
    raise AssertionError('timed out after %.1f s waiting for %s' % (timeout, what))


def build():
    """(native firmware, serial_node) paths; builds the firmware if needed."""
    package = rospkg.RosPack().get_path('pirate')
    return build_native_firmware(package), os.path.join(package, 'nodes', 'serial_node')


def start_fil(firmware):
    """Firmware in the loop on a fresh pty path, running."""
    fil = FirmwareInTheLoop(firmware, make_robot(),
                            os.path.join(tempfile.mkdtemp(prefix='pirate_fil_'), 'tty'))
    fil.start()
    return fil


def stop_fil(fil):
    fil.stop()
    os.rmdir(os.path.dirname(fil.link_path))


def spawn_serial_node(serial_node, link):
    """Our host as a child process on ``link`` (so a test can SIGKILL it)."""
    return subprocess.Popen([sys.executable, serial_node, '__name:=serial_node_%d' % os.getpid(),
                             '_port:=' + link],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def stop_process(proc):
    """SIGINT (serial_node sends TX_STOP), then SIGKILL after 5 s."""
    if proc.poll() is None:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(5)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def ros_sender():
    """send(name, msg) over ROS publishers; the control array latched, as the manager's."""
    pubs = {names.SETPOINT_TOPIC: rospy.Publisher(names.SETPOINT_TOPIC, SetpointArray,
                                                  queue_size=1),
            names.LIMITS_TOPIC: rospy.Publisher(names.LIMITS_TOPIC, LimitArray, queue_size=1),
            names.CONTROL_TOPIC: rospy.Publisher(names.CONTROL_TOPIC, ControlArray,
                                                 queue_size=1, latch=True)}
    return lambda name, msg: pubs[name].publish(msg)


def direct_sender(host):
    """send(name, msg) straight into a rosserial_python-rules host."""
    return lambda name, msg: host.publish(name, serialise(msg))


def control_codes(mode=0):
    """A control array: every element in ``mode``, PLAY at the command index."""
    codes = [mode] * 12
    codes[ControlArray.COMMAND_INDEX] = ControlArray.PLAY
    return codes


class Laptop(object):
    """The manager while playing: the control array once (and on change),
    setpoints and limits at 10 Hz. The setpoint counts in the camera tilt
    element; ``published`` keeps (time, value) of every setpoint sent."""

    def __init__(self, send):
        self.send = send
        self.published = []
        self.paused = threading.Event()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run)
        self._thread.daemon = True

    def start(self, codes=None):
        self.set_control(codes or control_codes())
        self._thread.start()

    def set_control(self, codes):
        self.control = list(codes)
        self.send(names.CONTROL_TOPIC, ControlArray(data=self.control))

    def _run(self):
        value = 0
        while not self._stop.is_set() and not rospy.is_shutdown():
            if not self.paused.is_set():
                value = value % 200 + 1
                self.published.append((time.monotonic(), value))
                self.send(names.LIMITS_TOPIC, LimitArray(data=[400, 400, 400, 400]))
                self.send(names.SETPOINT_TOPIC, SetpointArray(data=[value] + [0] * 12))
            self._stop.wait(0.1)

    def stop(self):
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(1.0)


class Bus(object):
    """What the simulated boards applied (``fil.boards.log``)."""

    def __init__(self, fil):
        self.fil = fil

    def sets(self, board, since=0.0):
        return [(t, c) for t, b, what, c in list(self.fil.boards.log)
                if b == board and what == 'set' and t >= since]

    def first_set(self, since):
        """Time of the first SET to any board at or after ``since``, or None."""
        times = [t for t, _, what, _ in list(self.fil.boards.log) if what == 'set' and t >= since]
        return min(times) if times else None

    def moving(self, since=0.0):
        return all(self.sets(20 + k, since) for k in range(BOARDS))

    def setpoint_frames(self, since=0.0):
        return [t for t, topic, payload in list(self.fil.host_frames)
                if len(payload) == SETPOINT_PAYLOAD and t >= since]

    def worst_staleness(self, published, board=20):
        """Largest age (s) of an applied setpoint counted from when the laptop
        replaced it; AssertionError if a board applied a value never sent."""
        worst = 0.0
        for applied_at, command in self.sets(board):
            pubs = [i for i, (t, v) in enumerate(published)
                    if v == command.setpoint0 and t <= applied_at]
            if not pubs:
                raise AssertionError('board applied %d, never published' % command.setpoint0)
            i = pubs[-1]
            if i + 1 < len(published) and published[i + 1][0] < applied_at:
                worst = max(worst, applied_at - published[i + 1][0])
        return worst
