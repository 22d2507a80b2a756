"""ROS edge of the rosserial host (the rosserial_python role).

Two threads around the pure parts:

- the *reader* opens the port (and reopens it after an unplug), feeds bytes
  to the :class:`~.protocol.FrameParser`, hands frames to the
  :class:`~.session.HostSession` and carries out what it asks: answer,
  create publishers/subscribers, publish device messages;
- the *writer* sends what ROS subscribers left in the :class:`~.outbox.Outbox`
  (latest value per topic, at most ``max_age`` old), only while the session
  is up. When the link goes down (silence, unplug) queued values and unsent
  port bytes are discarded; the firmware, for its part, ignores anything
  that reaches it after its watchdog tripped until a new handshake.

What a ros_lib device may use is served (firmware/README.md, "Host"):
publishers and subscribers (a topic announced again with another type is
recreated), services both ways (:mod:`.service_bridge_ros`), parameters from
the parameter server, logs at their level, time. A message larger than the
buffer the device announced for that topic is refused and logged at ERROR,
as rosserial_python does. Every lost sync is a WARN with its running count
and shows on ``/diagnostics`` at once. The laptop's command state survives
the link: the latest message of every *latched* publisher the device
subscribes to is re-sent whenever the link comes up and whenever the
device announces that subscriber again (after a reset), so control modes
reach the boards before any setpoint. Both are said on
``names.DEVICE_ANNOUNCED_TOPIC``: the manager holds the robot when a device
that streamed announces itself again (:mod:`pirate.manager.robot_link`).

Diagnostics through diagnostic_updater (task "serial link") at 1 Hz and at
every lost sync; a frame of another rosserial protocol version makes it
ERROR with rosserial_python's words, and is logged as an error.
"""
import io
import threading
import time

import diagnostic_updater
import rospy
import roslib.message
from diagnostic_msgs.msg import DiagnosticStatus, KeyValue
from std_msgs.msg import Empty

from pirate import names

from pirate.link import protocol, session as sessions
from pirate.link.port import SerialLink
from pirate.link.service_bridge_ros import ServiceBridge
from pirate.link.outbox import Outbox
from pirate.link.protocol import PROTOCOL_VERSION, FrameParser, encode

# rosserial_python's words, so a lab's search for them finds this too.
MISMATCHED_PROTOCOL = ('Mismatched protocol version in packet: lost sync or rosserial_python '
                       'is from different ros release than the rosserial client')

_LOG = {'debug': rospy.logdebug, 'info': rospy.loginfo, 'warn': rospy.logwarn,
        'error': rospy.logerr, 'fatal': rospy.logfatal}


class RosserialHost(object):
    """One device on one port. ``params``: see :func:`from_params`."""

    def __init__(self, port, baud, sync_timeout=0.5, max_age=0.2, clock=time.monotonic):
        self.link = SerialLink(port, baud)
        self.parser = FrameParser()
        self.session = sessions.HostSession(sync_timeout=sync_timeout)
        self.outbox = Outbox(max_age=max_age)
        self._clock = clock
        self._lock = threading.RLock()        # session + per-topic tables
        self._stop = threading.Event()
        self._publishers = {}                 # topic name -> (class, rospy.Publisher)
        self._subscribers = {}                # topic name -> rospy.Subscriber
        self._device_pub = {}                 # device topic id -> topic name
        self._latched = {}                    # topic name -> last payload of a latched publisher
        self._logged = {}
        self._updater = None
        self._last_lost_sync = 'never'
        self._versions_logged = set()
        self.counts = dict(frames_out=0, link_ups=0, link_downs=0, deserialize_errors=0,
                           not_up_dropped=0, oversize_refused=0, params_served=0)
        self.services = ServiceBridge(self._send_frame, self._warn, self._given_up)
        self._announced = rospy.Publisher(names.DEVICE_ANNOUNCED_TOPIC, Empty, queue_size=10)
        self._threads = [threading.Thread(target=self._read_loop, name='rosserial-reader'),
                         threading.Thread(target=self._write_loop, name='rosserial-writer')]

    @classmethod
    def from_params(cls):
        """Build from private params: ``~port`` (default /dev/ttyACM0), ``~baud``
        (57600, rosserial's default; 115200 supported), ``~sync_timeout`` (s,
        the shortest device silence that counts as lost sync, 0.5; the
        actual limit follows the device's own frame gaps, see
        :meth:`.session.HostSession.lost_after`), ``~max_age`` (s, oldest
        command ever sent, 0.2)."""
        return cls(rospy.get_param('~port', '/dev/ttyACM0'),
                   int(rospy.get_param('~baud', 57600)),
                   float(rospy.get_param('~sync_timeout', 0.5)),
                   float(rospy.get_param('~max_age', 0.2)))

    # -- lifecycle -----------------------------------------------------------
    def start(self):
        for thread in self._threads:
            thread.daemon = True
            thread.start()
        self._updater = diagnostic_updater.Updater()
        self._updater.setHardwareID(self.link.port_name)
        self._updater.add('serial link', self._fill_diagnostics)
        rospy.Timer(rospy.Duration(1.0), lambda _event: self._updater.update())
        rospy.on_shutdown(self.shutdown)

    def shutdown(self):
        """Tell the device we go (ID_TX_STOP), stop the threads, close the port."""
        if self._stop.is_set():
            return
        self._stop.set()
        with self._lock:
            self.link.write(self.session.tx_stop())
        for thread in self._threads:
            if thread is not threading.current_thread():
                thread.join(1.0)
        self.link.close()

    # -- logging ------------------------------------------------------------
    def _warn(self, text, level='logwarn'):
        """Log each distinct problem once, then every 100th repeat (at
        ``level``, the name of a rospy log function)."""
        count = self._logged.get(text, 0)
        self._logged[text] = count + 1
        if count % 100 == 0:
            getattr(rospy, level)('%s: %s%s', self.link.port_name, text,
                                  ' (x%d)' % (count + 1) if count else '')

    # -- reader -------------------------------------------------------------
    def _read_loop(self):
        while not self._stop.is_set():
            if not self.link.is_open:
                if not self._open():
                    self._stop.wait(0.5)
                continue
            data = self.link.read()
            now = self._clock()
            with self._lock:
                if data is None:
                    self._warn('port lost (%s); reopening' % self.link.last_error)
                    self._handle(self.session.closed())
                    continue
                for frame in self.parser.feed(data):
                    self._carry_out(*self.session.on_frame(frame, now, rospy.get_time()))
                self._check_version()
                self._carry_out(*self.session.tick(now))

    def _open(self):
        if not self.link.ensure_open():
            self._warn('cannot open port: %s' % self.link.last_error)
            return False
        rospy.loginfo('%s: open at %d baud, requesting topics', self.link.port_name,
                      self.link.baud)
        with self._lock:
            self.parser.reset()
            self.link.write(self.session.opened(self._clock()))
        return True

    def _carry_out(self, reply, events):
        """Events first: a link going down discards the port's unsent bytes,
        which must not take the topic request that follows with them."""
        self._handle(events)
        self.link.write(reply)

    def _handle(self, events):
        for event in events:
            try:
                getattr(self, '_on_' + event.kind)(event.data)
            except Exception as error:  # a device's bad input must not end the reader
                self._warn('cannot handle %s from the device: %s: %s'
                           % (event.kind, type(error).__name__, error))

    def _check_version(self):
        version = self.parser.last_version
        if version is not None and version not in self._versions_logged:
            self._versions_logged.add(version)
            rospy.logerr('%s: %s (device sent version byte 0x%02x, this host speaks 0x%02x)',
                         self.link.port_name, MISMATCHED_PROTOCOL, version,
                         PROTOCOL_VERSION)

    def _on_link(self, state):
        rospy.loginfo('%s: link %s', self.link.port_name, state)
        if state == sessions.UP:
            self.counts['link_ups'] += 1
            self._resend_latched(self._latched)
            self._announced.publish(Empty())
        else:
            # Nothing from before may reach the device: drop queued values and
            # whatever the port has not sent yet.
            self.counts['link_downs'] += 1
            self.outbox.clear()
            self.link.discard_output()

    def _on_error(self, text):
        self._warn(text)

    def _on_lost_sync(self, count_text):
        """Every episode: a WARN with the running count, and /diagnostics now."""
        count, text = count_text
        self._last_lost_sync = '#%d %s: %s' % (count, time.ctime(), text)
        rospy.logwarn('%s: lost sync with the device (%d so far): %s',
                      self.link.port_name, count, text)
        if self._updater is not None:
            self._updater.force_update()

    def _given_up(self, kind, name):
        """The service bridge will not answer the device's call (or stopped
        waiting for the device's answer): silence counts again."""
        with self._lock:
            self.session.given_up(kind, name, self._clock())

    def _on_log(self, level_text):
        level, text = level_text
        _LOG.get(level, rospy.loginfo)(text)

    def _on_param(self, name):
        """Answer from the parameter server; nothing (and an error) if it
        cannot be sent, as rosserial_python does."""
        try:
            reply = self.session.param_reply(rospy.get_param(name))
        except KeyError:
            rospy.logerr('Parameter %s does not exist', name)
            return
        except ValueError as error:
            rospy.logerr('Cannot send parameter %s: %s', name, error)
            return
        self.counts['params_served'] += 1
        self.link.write(reply)
        self.session.sent(protocol.ID_PARAMETER_REQUEST, self._clock())

    def _on_service(self, kind_part_info):
        self.services.announce(*kind_part_info)
        self.parser.max_payload = self.session.max_publish_size()

    def _on_service_frame(self, topic_payload):
        topic_id, payload = topic_payload
        kind, part, info = self.session.services[topic_id]
        self.services.on_frame(kind, part, info, payload)

    def _message_class(self, info):
        cls = roslib.message.get_message_class(info.message_type)
        if cls is None:
            self._warn('device topic %s has unknown type %s' % (info.topic_name, info.message_type))
            return None
        if cls._md5sum != info.md5sum:
            self._warn('device topic %s: md5 %s of %s does not match ours (%s); ignored'
                       % (info.topic_name, info.md5sum, info.message_type, cls._md5sum))
            return None
        return cls

    def _on_publisher(self, info):
        cls = self._message_class(info)
        if cls is None:
            return
        self._device_pub[info.topic_id] = info.topic_name
        self.parser.max_payload = self.session.max_publish_size()
        old = self._publishers.get(info.topic_name)
        if old is not None and old[0] is cls:
            return
        if old is not None:   # renegotiated with another type
            old[1].unregister()
        rospy.loginfo('%s: device publishes %s [%s]', self.link.port_name,
                      info.topic_name, info.message_type)
        self._publishers[info.topic_name] = (
            cls, rospy.Publisher(info.topic_name, cls, queue_size=50))

    def _on_subscriber(self, info):
        cls = self._message_class(info)
        if cls is None:
            return
        name = info.topic_name
        old = self._subscribers.get(name)
        if old is not None and old.data_class is cls:
            # Announced again (a reset device): give it the laptop's state.
            if self.session.state == sessions.UP:
                self._resend_latched({name: self._latched[name]} if name in self._latched else {})
                self._announced.publish(Empty())
            return
        if old is not None:   # renegotiated with another type
            old.unregister()
            self._latched.pop(name, None)
        rospy.loginfo('%s: device subscribes %s [%s]', self.link.port_name,
                      name, info.message_type)
        self._subscribers[name] = rospy.Subscriber(
            name, cls, lambda msg: self._forward(name, msg), queue_size=1)

    def _on_message(self, topic_payload):
        topic_id, payload = topic_payload
        name = self._device_pub.get(topic_id)
        if name is None:
            return
        cls, publisher = self._publishers[name]
        msg = cls()
        try:
            msg.deserialize(payload)
        except Exception as error:  # genpy raises several types on short data
            self.counts['deserialize_errors'] += 1
            self._warn('cannot deserialize %s from device: %s' % (name, error))
            return
        publisher.publish(msg)

    # -- writer -------------------------------------------------------------
    def _forward(self, name, msg):
        """ROS subscriber callback: keep the latest serialised value (and, from
        a latched publisher, remember it as state to restore)."""
        buff = io.BytesIO()
        msg.serialize(buff)
        header = getattr(msg, '_connection_header', None) or {}
        if header.get('latching') == '1':
            self._latched[name] = buff.getvalue()
        self.outbox.put(name, buff.getvalue(), self._clock())

    def _resend_latched(self, payloads):
        now = self._clock()
        for name, payload in list(payloads.items()):
            self.outbox.put(name, payload, now)

    def _send_frame(self, topic_id, payload, name=None):
        """Write one frame to the device if the link is up and it fits the
        buffer the device announced; True if written."""
        with self._lock:
            if self.session.state != sessions.UP or not self.link.is_open:
                return False
            size = self.session.buffer_size(topic_id)
            if size and len(payload) > size:
                self.counts['oversize_refused'] += 1
                self._warn('Message from ROS network dropped: message larger than buffer '
                           '(%s: %d bytes, the device\'s buffer %d)'
                           % (name or topic_id, len(payload), size), 'logerr')
                return False
            if not self.link.write(encode(topic_id, payload)):
                return False
            self.session.sent(topic_id, self._clock())
            self.counts['frames_out'] += 1
            return True

    def _write_loop(self):
        while not self._stop.is_set():
            if not self.outbox.wait(0.05):
                continue
            now = self._clock()
            with self._lock:
                up = self.session.state == sessions.UP and self.link.is_open
            if not up:
                self.counts['not_up_dropped'] += len(self.outbox.take(now))
                continue
            for name, payload in self.outbox.take(now):
                with self._lock:
                    info = self.session.subscriber(name)
                if info is not None:
                    self._send_frame(info.topic_id, payload, name)

    # -- diagnostics ----------------------------------------------------------
    def diagnostic_values(self):
        """Every counter of the link, by name (frames, errors, link changes)."""
        stats = self.parser.stats
        values = dict(self.counts)
        values.update(state=self.session.state, frames_in=stats.frames,
                      bytes_in=self.link.bytes_in, bytes_out=self.link.bytes_out,
                      checksum_errors=stats.checksum_errors,
                      length_errors=stats.length_errors, resyncs=self.parser.resyncs,
                      lost_syncs=self.session.lost_syncs,
                      stale_dropped=self.outbox.stale_dropped,
                      replaced=self.outbox.replaced, baud=self.link.baud,
                      version_errors=stats.version_errors,
                      lost_after_s=round(self.session.lost_after(), 3),
                      last_lost_sync=self._last_lost_sync,
                      device_waits=' '.join('%s %s' % w for w in
                                            self.session.device_waits(self._clock())) or 'none')
        return values

    def diagnostic_status(self):
        """The link's DiagnosticStatus: OK up, WARN negotiating, ERROR down or
        when the device speaks another protocol version."""
        values = self.diagnostic_values()
        status = DiagnosticStatus(name='pirate: serial link %s' % self.link.port_name,
                                  hardware_id=self.link.port_name)
        state = values['state']
        status.level = {sessions.UP: DiagnosticStatus.OK,
                        sessions.NEGOTIATING: DiagnosticStatus.WARN}.get(state, DiagnosticStatus.ERROR)
        status.message = 'link %s' % state
        if self.session.lost_syncs:
            status.message += ' (lost sync %d times)' % self.session.lost_syncs
        if self.parser.last_version is not None:
            status.level = DiagnosticStatus.ERROR
            status.message = MISMATCHED_PROTOCOL
        status.values = [KeyValue(k, str(v)) for k, v in sorted(values.items())]
        return status

    def _fill_diagnostics(self, stat):
        """diagnostic_updater task: :meth:`diagnostic_status` into ``stat``."""
        status = self.diagnostic_status()
        stat.summary(status.level, status.message)
        for pair in status.values:
            stat.add(pair.key, pair.value)
        return stat
