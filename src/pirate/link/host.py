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

Diagnostics (diagnostic_msgs/DiagnosticArray on /diagnostics) at 1 Hz.
"""
import io
import threading
import time

import rospy
import roslib.message
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue

from pirate.link import session as sessions
from pirate.link.port import SerialLink
from pirate.link.outbox import Outbox
from pirate.link.protocol import FrameParser, encode

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
        self._logged = {}
        self.counts = dict(frames_out=0, link_ups=0, link_downs=0, deserialize_errors=0,
                           not_up_dropped=0)
        self._diag_pub = rospy.Publisher('/diagnostics', DiagnosticArray, queue_size=2)
        self._threads = [threading.Thread(target=self._read_loop, name='rosserial-reader'),
                         threading.Thread(target=self._write_loop, name='rosserial-writer')]

    @classmethod
    def from_params(cls):
        """Build from private params: ``~port`` (default /dev/ttyACM0), ``~baud``
        (57600, rosserial's default; 115200 supported), ``~sync_timeout`` (s of
        device silence before the link counts as lost and topics are
        requested again; 0.5 suits the Pirate Bay, which streams Small State
        every 100 ms; use about 6 for a device that publishes nothing and
        only syncs time), ``~max_age`` (s, oldest command ever sent, 0.2)."""
        return cls(rospy.get_param('~port', '/dev/ttyACM0'),
                   int(rospy.get_param('~baud', 57600)),
                   float(rospy.get_param('~sync_timeout', 0.5)),
                   float(rospy.get_param('~max_age', 0.2)))

    # -- lifecycle -----------------------------------------------------------
    def start(self):
        for thread in self._threads:
            thread.daemon = True
            thread.start()
        rospy.Timer(rospy.Duration(1.0), lambda _event: self.publish_diagnostics())
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
    def _warn(self, text):
        """Log each distinct problem once, then every 100th repeat."""
        count = self._logged.get(text, 0)
        self._logged[text] = count + 1
        if count % 100 == 0:
            rospy.logwarn('%s: %s%s', self.link.port_name, text,
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
                    reply, events = self.session.on_frame(frame, now, rospy.get_time())
                    self.link.write(reply)
                    self._handle(events)
                reply, events = self.session.tick(now)
                self.link.write(reply)
                self._handle(events)

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

    def _handle(self, events):
        for event in events:
            getattr(self, '_on_' + event.kind)(event.data)

    def _on_link(self, state):
        rospy.loginfo('%s: link %s', self.link.port_name, state)
        if state == sessions.UP:
            self.counts['link_ups'] += 1
        else:
            # Nothing from before may reach the device: drop queued values and
            # whatever the port has not sent yet.
            self.counts['link_downs'] += 1
            self.outbox.clear()
            self.link.discard_output()

    def _on_error(self, text):
        self._warn(text)

    def _on_log(self, level_text):
        level, text = level_text
        _LOG.get(level, rospy.loginfo)('device: %s', text)

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
        if info.topic_name not in self._publishers:
            rospy.loginfo('%s: device publishes %s [%s]', self.link.port_name,
                          info.topic_name, info.message_type)
            self._publishers[info.topic_name] = (
                cls, rospy.Publisher(info.topic_name, cls, queue_size=50))

    def _on_subscriber(self, info):
        cls = self._message_class(info)
        if cls is None or info.topic_name in self._subscribers:
            return
        rospy.loginfo('%s: device subscribes %s [%s]', self.link.port_name,
                      info.topic_name, info.message_type)
        name = info.topic_name
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
        """ROS subscriber callback: keep the latest serialised value."""
        buff = io.BytesIO()
        msg.serialize(buff)
        self.outbox.put(name, buff.getvalue(), self._clock())

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
                    topic_id = self.session.subscriber_id(name)
                    if topic_id is None:
                        continue
                    if self.link.write(encode(topic_id, payload)):
                        self.counts['frames_out'] += 1

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
                      replaced=self.outbox.replaced, baud=self.link.baud)
        return values

    def publish_diagnostics(self):
        values = self.diagnostic_values()
        status = DiagnosticStatus(name='pirate: serial link %s' % self.link.port_name,
                                  hardware_id=self.link.port_name)
        state = values['state']
        status.level = {sessions.UP: DiagnosticStatus.OK,
                        sessions.NEGOTIATING: DiagnosticStatus.WARN}.get(state, DiagnosticStatus.ERROR)
        status.message = 'link %s' % state
        status.values = [KeyValue(k, str(v)) for k, v in sorted(values.items())]
        array = DiagnosticArray(status=[status])
        array.header.stamp = rospy.Time.now()
        self._diag_pub.publish(array)
