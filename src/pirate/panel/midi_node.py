"""The MIDI driver nodes: panel -> MidiInput, MidiOutput -> panel LEDs.

``midi_input``: publishes a pirate/MidiInput on ``names.MIDI_INPUT_TOPIC``
for every control change the panel sends, and on ``names.PANEL_DEVICE_TOPIC``
(latched std_msgs/Bool) whether it has the panel (the Mapper pauses a
mission when the panel is unplugged). ``midi_output``: subscribes
``names.MIDI_OUTPUT_TOPIC`` and lights the button LEDs. Both choose the
device by ``~device`` (an id or part of the name from ``midi_devices``;
'' = the first panel found), wait with a clear message while it is absent,
and reopen it after an unplug without a restart (pirate.panel.midi).
Private params: ``~device``, ``~poll_hz`` (input polling, default 200),
``~retry_s`` (how often to look for a missing device, default 1).
"""
import sys
import threading
import time

import diagnostic_updater
import rospy

from pirate import health, names
from pirate.msg import MidiInput, MidiOutput
from std_msgs.msg import Bool
from pirate.panel import midi
from pirate.panel.midi_backend import PygameMidiBackend


def _link(want_input):
    """The MIDI link, with a 'panel device' diagnostic (diagnostic_updater) at 1 Hz."""
    wanted = str(rospy.get_param('~device', ''))
    link = midi.MidiLink(PygameMidiBackend(), wanted, want_input,
                         rospy.logwarn, retry_s=float(rospy.get_param('~retry_s', 1.0)))
    updater = diagnostic_updater.Updater()
    updater.setHardwareID('nanoKONTROL2 %s' % wanted)
    updater.add('panel device', lambda stat: health.fill(stat, health.panel_device(
        link.connected, wanted, link.info.name if link.connected and link.info else '')))
    rospy.Timer(rospy.Duration(1.0), lambda _event: updater.update())
    return link


def main_input():
    """Poll the panel and publish every control change."""
    if '--list' in sys.argv:
        return main_devices()
    rospy.init_node('midi_input')
    pub = rospy.Publisher(names.MIDI_INPUT_TOPIC, MidiInput, queue_size=200)
    device_pub = rospy.Publisher(names.PANEL_DEVICE_TOPIC, Bool, queue_size=1, latch=True)
    link = _link(True)
    rate = rospy.Rate(float(rospy.get_param('~poll_hz', 200.0)))
    had = None
    while not rospy.is_shutdown():
        link.step(time.monotonic())
        if link.connected != had:
            had = link.connected
            device_pub.publish(Bool(data=had))
        for channel, value in link.read():
            pub.publish(MidiInput(channel=channel, value=value))
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


def main_output():
    """Light the panel's LEDs from MidiOutput; remember them across an unplug."""
    rospy.init_node('midi_output')
    link = _link(False)
    lock = threading.Lock()
    leds = {}
    pending = set()

    def on_led(msg):
        with lock:
            leds[msg.button] = msg.value
            pending.add(msg.button)

    rospy.Subscriber(names.MIDI_OUTPUT_TOPIC, MidiOutput, on_led, queue_size=200)
    rate = rospy.Rate(50)
    was_connected = False
    while not rospy.is_shutdown():
        connected = link.step(time.monotonic())
        with lock:
            if connected and not was_connected:
                pending.update(leds)   # a (re)plugged panel gets every LED again
            todo = sorted(pending) if connected else []
            for button in todo:
                if link.write_led(button, leds[button]):
                    pending.discard(button)
        was_connected = link.connected
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


def main_devices():
    """Print the MIDI devices present (for choosing ~device)."""
    backend = PygameMidiBackend()
    backend.rescan()
    print(midi.describe(backend.devices()))
    return 0
