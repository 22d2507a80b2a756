"""The safe hold is atomic on the wire.

Whatever is in flight (a primitive switching modes, the 10 Hz tick, a Stop
from the panel thread), after a Stop, cancel, abort or shutdown the last
control and setpoint arrays *published* are the hold's: bends and front
module in PWM with setpoint 0, wheels 0. Checked on the recorded wire, not
on the objects.
"""
import random
import threading
import time

import pytest

from pirate.robot import commands
from pirate.robot.hold import safe_hold
from pirate.sequencer.primitives import MotionPrimitives
from pirate.testing.harness import SimHarness
from pirate.state.feed import Cancelled, RobotFeed

HOLD_PWM = (1, 2, 3, 6, 7)      # front tilt, Bend I, II, III, IV (Table 4.1/4.2)
WHEELS = 11
STOPS = 500
CLAMP_STRAIGHT, HOME = 0, 5


def hold_is_last(control_sent, setpoint_sent):
    """(True, '') when the newest arrays on the wire are the hold's, else (False, why)."""
    control, setpoint = control_sent[-1], setpoint_sent[-1]
    if any(control[i] != 0 for i in HOLD_PWM):
        return False, 'control %s' % control
    if any(setpoint[i] != 0 for i in HOLD_PWM + (WHEELS,)):
        return False, 'setpoint %s' % setpoint
    return True, ''


class GatedWire(object):
    """A publisher whose next publish blocks until released (a slow transport)."""

    def __init__(self):
        self.sent = []
        self.gate = threading.Event()
        self.entered = threading.Event()
        self.armed = False

    def publish(self, data):
        if self.armed:
            self.armed = False
            self.entered.set()
            self.gate.wait(10.0)
        self.sent.append(list(data))


def test_a_mode_change_in_flight_never_lands_after_the_hold():
    """The PAB's torque array is being sent when the Stop's hold starts."""
    control_wire, setpoint_wire = GatedWire(), GatedWire()
    control = commands.Control(control_wire, list)
    setpoint = commands.Setpoint(setpoint_wire, list, control)
    control_wire.armed = True
    pab = threading.Thread(target=control.set_mode, args=('bend_iv', 'torque'))
    pab.start()
    assert control_wire.entered.wait(10.0)
    stop = threading.Thread(target=safe_hold, args=(setpoint, control))
    stop.start()
    stop.join(0.2)          # give a lock-free hold the chance to finish first (the old race)
    control_wire.gate.set()
    pab.join(10.0)
    stop.join(10.0)
    assert hold_is_last(control_wire.sent, setpoint_wire.sent) == (True, '')


def test_a_cancelled_pab_writes_nothing_more():
    control_sent, setpoint_sent = [], []
    control = commands.Control(type('W', (), {'publish': staticmethod(control_sent.append)})(), list)
    setpoint = commands.Setpoint(type('W', (), {'publish': staticmethod(setpoint_sent.append)})(),
                                 list, control)
    feed = RobotFeed()
    feed.push(None)
    prims = MotionPrimitives(setpoint, control, None, feed)
    feed.cancel()
    with pytest.raises(Cancelled):
        prims.change_control_mode('bend_iv', 'torque')
    assert control_sent == [] and control.mode_of('bend_iv') == 'pwm'


def _stop(h, how):
    """A Stop from another thread (panel, shutdown) or a cancel (actionlib)."""
    h.server.cancel()
    if how == 'stop':
        h.control.command('stop')
        safe_hold(h.setpoint, h.control, h.feed.latest().angles)


def _yielding(publish):
    """rospy's publish hands the message to its thread: other threads run meanwhile."""
    def wrapped(data):
        time.sleep(0)
        publish(data)
    return wrapped


def test_the_hold_is_last_on_the_wire_after_stops_at_random_instants():
    rng = random.Random(13)
    stopped, wrong = 0, []
    with SimHarness() as h:
        for wire in h.wires.values():
            wire.publish = _yielding(wire.publish)
        goal = CLAMP_STRAIGHT
        while stopped < STOPS:
            reason = h.server.reserve(h.goal(goal))
            assert reason is None, reason
            result = {}
            worker = threading.Thread(target=lambda g=h.goal(goal): result.update(o=h.execute_reserved(g)))
            worker.start()
            threading.Event().wait(rng.uniform(0.0, 0.03))     # the random instant (wall)
            how = rng.choice(('stop', 'cancel'))
            _stop(h, how)
            worker.join(30.0)
            assert not worker.is_alive()
            if result['o'].status == 'succeeded':
                goal = HOME if goal == CLAMP_STRAIGHT else CLAMP_STRAIGHT   # ended before the stop
                continue
            stopped += 1
            h.run_for(0.3)                                    # let the 10 Hz tick run on
            ok, why = hold_is_last([d for _, d in h.wires['control'].sent],
                                   [d for _, d in h.wires['setpoint'].sent])
            if not ok:
                wrong.append((how, h.server.state, why))
    assert wrong == [], '%d of %d stops: %s' % (len(wrong), stopped, wrong[:3])
