"""The manager's link watch: the first Small State after a silence brings
the laptop's control modes and limits back to the device, before any
setpoint, whichever host runs the link; after a silence the setpoints at
the safe hold first. No ROS."""
import threading

import pytest

from pirate.robot import commands, link_watch, tables
from pirate.robot.link_watch import LinkWatch


def test_the_first_message_ever_is_the_link_coming_up():
    watch = LinkWatch()
    assert watch.heard(100.0) == link_watch.UP and watch.returns == 1


def test_a_steady_stream_gets_the_state_once_a_second():
    watch = LinkWatch(silence_s=0.15, refresh_s=1.0)
    sends = [(k * 0.011, watch.heard(k * 0.011)) for k in range(500)]
    sends = [(t, what) for t, what in sends if what]
    assert [t for t, _ in sends] == pytest.approx([0.0, 1.001, 2.002, 3.003, 4.004, 5.005])
    assert [what for _, what in sends] == [link_watch.UP] + [link_watch.REFRESH] * 5
    assert watch.returns == 1


def test_the_first_message_after_a_silence_is_the_link_back_once():
    watch = LinkWatch(silence_s=0.15, refresh_s=1.0)
    watch.heard(0.0)
    assert not watch.heard(0.15)
    assert watch.heard(0.55) == link_watch.UP      # a stall, a late laptop: no Small State
    assert not watch.heard(0.56)
    assert watch.returns == 2
    stream = [0.56 + k * 0.011 for k in range(1, 100)]
    assert [t for t in stream if watch.heard(t)] == pytest.approx([1.55])    # a second after the return


def test_a_long_silence_is_the_robot_back():
    watch = LinkWatch(silence_s=0.15, refresh_s=1.0, reset_silence_s=0.5)
    watch.heard(0.0)
    assert watch.heard(0.5) == link_watch.UP
    assert watch.heard(1.01) == link_watch.BACK    # an unplug, a reset in its bootloader
    assert not watch.heard(1.02)
    assert watch.returns == 3


def test_an_announcement_after_the_stream_is_the_link_back_once():
    watch = LinkWatch(silence_s=0.15, refresh_s=1.0)
    assert watch.announced() is None             # the link up: nothing streamed yet
    watch.heard(0.0)
    watch.heard(0.1)
    assert watch.announced() == link_watch.BACK  # a reset too short to be silence
    assert watch.heard(0.2) == link_watch.UP     # not a second return
    assert not watch.heard(0.3)


class Wire(object):
    """Publishers of the three arrays, all writing one record, in order."""

    def __init__(self):
        self.sent = []

    def publisher(self, name):
        wire = self

        class Publisher(object):
            def publish(self, msg):
                wire.sent.append((name, msg))
        return Publisher()


def test_restore_sends_control_then_limits_with_the_laptops_values():
    wire = Wire()
    control = commands.Control(wire.publisher('control'), list)
    limit = commands.Limit(wire.publisher('limits'), list)
    control.set_mode('bend_i', 'torque')
    limit.set('bend_i', 400)
    del wire.sent[:]
    link_watch.restore(control, limit)
    assert [name for name, _ in wire.sent] == ['control', 'limits']
    assert wire.sent[0][1] == control.get_all() and wire.sent[1][1] == limit.get_all()


def test_no_setpoint_slips_between_control_and_limits():
    wire = Wire()
    control = commands.Control(wire.publisher('control'), list)
    setpoint = commands.Setpoint(wire.publisher('setpoint'), list, control)
    limit = commands.Limit(wire.publisher('limits'), list)
    setpoint.enabled = True
    entered, release = threading.Event(), threading.Event()

    class SlowLimits(object):
        def publish(self, msg):
            entered.set()
            release.wait(5.0)
            wire.sent.append(('limits', msg))
    limit._publisher = SlowLimits()   # pylint: disable=protected-access
    restoring = threading.Thread(target=link_watch.restore, args=(control, limit))
    restoring.start()
    assert entered.wait(5.0)
    ticking = threading.Thread(target=setpoint.tick)
    ticking.start()
    ticking.join(0.2)                    # the setpoint waits for the wire lock
    release.set()
    restoring.join(5.0)
    ticking.join(5.0)
    assert [name for name, _ in wire.sent] == ['control', 'limits', 'setpoint']


def test_hold_and_restore_sends_the_hold_then_control_then_limits():
    wire = Wire()
    control = commands.Control(wire.publisher('control'), list)
    setpoint = commands.Setpoint(wire.publisher('setpoint'), list, control)
    limit = commands.Limit(wire.publisher('limits'), list)
    control.set_mode('bend_i', 'torque')
    setpoint.set('bend_i', 188)
    setpoint.set('wheels', 37)
    del wire.sent[:]
    link_watch.hold_and_restore(setpoint, control, limit)
    names = [name for name, _ in wire.sent]
    assert names[0] == 'setpoint' and names[-2:] == ['control', 'limits']
    assert wire.sent[0][1][tables.element('bend_i').index] == 0
    assert wire.sent[0][1][tables.element('wheels').index] == 0
    assert control.mode_of('bend_i') == 'pwm'
