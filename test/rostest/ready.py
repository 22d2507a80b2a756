"""Shared by the rostests that send goals: wait until the stack can take one."""
import time

import rospy

from pirate import names
from pirate.robot import tables
from pirate.srv import ServerStatus

#: The joints the safe hold puts in PWM mode at 0.
HOLD_PWM = ('front_tilt', 'bend_i', 'bend_ii', 'bend_iii', 'bend_iv')


def wait_robot_connected(timeout_s=60.0):
    """Block until the Pirate Server reports a fresh robot state; AssertionError if not."""
    status = rospy.ServiceProxy(names.SERVER_STATUS_SERVICE, ServerStatus)
    status.wait_for_service(timeout_s)
    deadline = time.monotonic() + timeout_s
    while not status().robot_connected:
        if time.monotonic() > deadline:
            raise AssertionError('the Pirate Server saw no robot state within %.0f s' % timeout_s)
        time.sleep(0.1)   # poll the status service


def wait_until(condition, what, deadline_s=60.0):
    """Poll ``condition`` (every 20 ms) until truthy and return that value;
    AssertionError naming ``what`` after the deadline."""
    end = time.monotonic() + deadline_s
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > end:
            raise AssertionError('timed out after %.0f s waiting for %s' % (deadline_s, what))
        time.sleep(0.02)


def wait_panel_goals_connected(timeout_s=30.0):
    """Block until pirate_manager's diagnostics say the panel's PAB goals reach
    the Pirate Server (a press before is refused, 'press again'); AssertionError if not."""
    from diagnostic_msgs.msg import DiagnosticArray
    from pirate import health
    connected = health.panel_goals(True).message
    heard = []
    ear = rospy.Subscriber('/diagnostics', DiagnosticArray, lambda msg: heard.extend(
        s.message for s in msg.status if s.name.endswith('panel goals')))
    try:
        wait_until(lambda: connected in heard, 'the panel to reach the Pirate Server (diagnostics)', timeout_s)
    finally:
        ear.unregister()


def wait_hold_on_wire(controls, setpoints):
    """Wait until the last of ``controls`` / ``setpoints`` (lists of the
    arrays heard on the wire) are the safe hold: :data:`HOLD_PWM` in PWM,
    those and the wheels at 0."""
    index = {name: tables.element(name).index for name in HOLD_PWM + ('wheels',)}
    wait_until(lambda: controls and all(controls[-1].data[index[n]] == 0 for n in HOLD_PWM),
               'PWM modes of the hold on the wire')
    wait_until(lambda: setpoints and all(setpoints[-1].data[i] == 0 for i in index.values()),
               'the hold setpoints on the wire')
