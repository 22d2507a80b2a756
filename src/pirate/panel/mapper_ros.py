"""ROS edge of the Mapper, composed inside the pirate_manager node.

Construct after ``rospy.init_node`` in the node that owns the shared
Setpoint / Control / Limit objects (report 4.5: one instance of each)::

    panel = MapperRos(setpoint, control, limit, pab_client)

- reads the panel map from the node's private params (``~channels`` etc.,
  loaded from ``config/nanokontrol2.yaml`` by Manager.launch) unless a
  ``config`` dict/PanelConfig is given;
- subscribes MidiInput on ``names.MIDI_INPUT_TOPIC`` (queue 100: under a
  flood rospy drops the oldest events, so a Stop press is never stuck
  behind thousands of slider values);
- publishes MidiOutput on ``names.MIDI_OUTPUT_TOPIC``; every LED is sent
  again when a panel driver or virtual panel connects;
- tells the operator (refusals, results, mode changes) at INFO on rosout
  and on ``names.OPERATOR_TOPIC`` (latched), which the virtual panel shows;
- runs a 10 Hz timer that calls ``mapper.tick()`` (LEDs follow modes a PAB
  changed) and, unless ``publish_arrays=False``, ``setpoint.tick()`` and
  ``limit.tick()`` (the 10 Hz publishing of report 4.6; pass False if the
  node ticks them itself);
- the mission: follows the mission executive's feedback and result
  (``names.MISSION_ACTION``) and sends the mission buttons' commands to
  its ``names.MISSION_COMMAND_SERVICE`` from a worker thread (a slow or
  absent executive never blocks the panel); a mission whose executive is
  silent (no action status) for ``MISSION_SILENCE_S`` is dropped;
- the mark button: calls the inspection recorder's
  ``names.INSPECTION_MARK_SERVICE`` (kind ``other``) from a worker thread
  and tells the operator its answer;
- the panel's presence (pirate.panel.presence): the publishers of
  ``names.MIDI_INPUT_TOPIC`` and the MIDI driver's word on
  ``names.PANEL_DEVICE_TOPIC``, checked every tick.
"""
import queue
import threading
import time

import rospy

from pirate import names
from pirate.panel.mapper import Mapper
from pirate.panel.mission_buttons import ExecutiveWatch
from pirate.panel.presence import PanelPresence
from pirate.msg import MidiInput, MidiOutput, MissionActionFeedback, MissionActionResult
from pirate.srv import InspectionMark, MissionCommand
from actionlib_msgs.msg import GoalStatusArray
from std_msgs.msg import Bool, String

TICK_PERIOD_S = 0.1
#: How long a mission command waits for the executive's service, wall s.
MISSION_SERVICE_WAIT_S = 2.0
#: Wall s without the executive's action status before the panel drops its mission.
MISSION_SILENCE_S = 3.0


class _ServiceCalls(object):
    """Calls to one service, in order, from one worker thread, so a panel
    callback never blocks on a node that is slow or gone; each call ends in
    ``answered(answer)`` or ``failed(error)``."""

    def __init__(self, service, service_type, thread_name):
        self._todo = queue.Queue()
        self._proxy = rospy.ServiceProxy(service, service_type)
        threading.Thread(target=self._work, name=thread_name, daemon=True).start()

    def call(self, request, answered, failed):
        """Queue a call with ``request`` (the service's request fields)."""
        self._todo.put((request, answered, failed))

    def _work(self):
        while not rospy.is_shutdown():
            request, answered, failed = self._todo.get()
            try:
                self._proxy.wait_for_service(MISSION_SERVICE_WAIT_S)
                answer = self._proxy(**request)
            except (rospy.ROSException, rospy.ServiceException) as err:
                failed(err)
                continue
            answered(answer)


class MissionCommandClient(object):
    """The mapper's mission client: commands go out in order; each answer
    goes back to ``reply(command, ok, message)``."""

    def __init__(self):
        self.reply = None
        self._calls = _ServiceCalls(names.MISSION_COMMAND_SERVICE, MissionCommand, 'mission_commands')

    def command(self, text):
        self._calls.call({'command': text}, lambda answer: self._answer(text, answer.ok, answer.message),
                         lambda err: self._answer(text, False, 'no mission executive answers (%s)' % err))

    def _answer(self, text, ok, message):
        if self.reply is not None:
            self.reply(text, ok, message)


class FindingClient(object):
    """The mapper's mark button: each press marks a finding of kind
    ``other`` through the inspection recorder's service; its answer goes
    to ``tell(text)``."""

    def __init__(self, tell):
        self._tell = tell
        self._calls = _ServiceCalls(names.INSPECTION_MARK_SERVICE, InspectionMark, 'finding_marks')

    def mark(self, note):
        self._calls.call({'kind': 'other', 'note': note}, lambda answer: self._tell(answer.message),
                         lambda err: self._tell('finding not marked: no inspection recorder answers (%s)' % err))


class _LedResync(rospy.SubscribeListener):
    """Send every LED to a panel that has just subscribed."""

    def __init__(self, owner):
        super(_LedResync, self).__init__()
        self._owner = owner

    def peer_subscribe(self, topic_name, topic_publish, peer_publish):
        if self._owner.mapper is not None:
            self._owner.mapper.refresh_leds(force=True)


class MapperRos(object):
    """Wire a :class:`pirate.panel.mapper.Mapper` to the panel topics and a 10 Hz timer."""

    def __init__(self, setpoint, control, limit, pab_client, config=None, publish_arrays=True):
        self.mapper = None
        self._setpoint, self._limit = setpoint, limit
        self._publish_arrays = publish_arrays
        self._led_pub = rospy.Publisher(names.MIDI_OUTPUT_TOPIC, MidiOutput, queue_size=100,
                                        subscriber_listener=_LedResync(self))
        self._operator_pub = rospy.Publisher(names.OPERATOR_TOPIC, String, queue_size=20, latch=True)
        if config is None:
            config = rospy.get_param('~')
        mission = MissionCommandClient()
        self.mapper = Mapper(config, setpoint, control, limit, pab_client,
                             self._publish_led, self._tell, time.monotonic, mission=mission,
                             finding=FindingClient(self._tell))
        mission.reply = self.mapper.mission_reply
        self._presence = PanelPresence()
        self._executive = ExecutiveWatch(MISSION_SILENCE_S)
        self._sub = rospy.Subscriber(names.MIDI_INPUT_TOPIC, MidiInput, self._on_midi,
                                     queue_size=100)
        self._others = [
            rospy.Subscriber(names.PANEL_DEVICE_TOPIC, Bool, lambda msg: self._presence.device(msg.data)),
            rospy.Subscriber(names.MISSION_ACTION + '/status', GoalStatusArray,
                             lambda msg: self._executive.heard(time.monotonic()), queue_size=1),
            rospy.Subscriber(names.MISSION_ACTION + '/feedback', MissionActionFeedback,
                             lambda msg: self.mapper.mission_progress(msg.feedback), queue_size=10),
            rospy.Subscriber(names.MISSION_ACTION + '/result', MissionActionResult,
                             lambda msg: self.mapper.mission_ended(msg.result.status, msg.result.message),
                             queue_size=10)]
        self._timer = rospy.Timer(rospy.Duration(TICK_PERIOD_S), self._tick)

    def _publish_led(self, button, on):
        self._led_pub.publish(MidiOutput(button=button, value=on))

    def _tell(self, text):
        rospy.loginfo('panel: %s', text)
        self._operator_pub.publish(String(data=text))

    def _on_midi(self, msg):
        self.mapper.handle(msg.channel, msg.value)

    def _tick(self, _event):
        change = self._presence.update(self._sub.get_num_connections())
        if change is not None:
            self.mapper.panel_connected(*change)
        if self._executive.lost(time.monotonic(), self.mapper.mission.active):
            self.mapper.mission_ended('lost', 'no word from the mission executive for %.0f s; the PAB '
                                      'buttons are yours again' % MISSION_SILENCE_S)
        self.mapper.tick()
        if self._publish_arrays:
            self._setpoint.tick()
            self._limit.tick()

    def shutdown(self):
        """Stop the timer and the subscription (node shutdown, tests)."""
        self._timer.shutdown()
        for sub in [self._sub] + self._others:
            sub.unregister()
