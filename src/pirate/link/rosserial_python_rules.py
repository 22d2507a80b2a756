"""A host that follows rosserial_python's rules, for FIL tests and benches.

Labs run rosserial_python (noetic-devel 0.9.x, ``SerialClient.py``) as the
host of this firmware. Its code may not enter this project, so this module
re-states the rules of it that decide whether and when a device recovers,
from its documented behaviour (firmware/README.md, "Host"), without ROS:

- topics are requested once at start; after that only when no time request
  came for 3 x its 5 s timeout (``lastsync``: 15 s), or when a frame arrives
  on a topic id it has no callback for ("Tried to publish before
  configured");
- TopicInfo is taken at any time; a subscriber is created once per topic
  name and never re-sent anything (a latched value reaches the device once);
- every time request is answered at once and resets ``lastsync``;
- outgoing messages go through one FIFO queue (no age limit, no latest-value
  rule: what was queued during a stall is all sent afterwards), written by
  a thread that sleeps 10 ms when the queue is empty; a message larger than
  the first subscriber buffer the device announced is dropped.

Messages are serialised bytes here: :meth:`publish` stands for the ROS
subscriber callback. Received frames are kept in ``received`` as
(time, topic name, payload). Time is ``clock()`` (s).
"""
import io
import queue
import threading
import time

from pirate.link import messages, protocol
from pirate.link.port import SerialLink

LASTSYNC_S = 3 * 5.0         # 3 x SerialClient's default timeout
WRITE_IDLE_S = 0.01


class RosserialPythonRules(object):
    """One device on ``port``; ``start()``, then ``publish(name, payload)``."""

    def __init__(self, port, baud=57600, clock=time.monotonic):
        self.link = SerialLink(port, baud)
        self.clock = clock
        self.parser = protocol.FrameParser()
        self.publisher_names = {}     # device topic id -> name (callbacks; never cleared)
        self.subscriber_ids = {}      # name -> device topic id
        self.buffer_in = -1
        self.received = []            # (time, topic name, payload)
        self.logs = []                # (level, text)
        self.topic_requests = 0
        self.lost_syncs = 0
        self.lastsync = None
        self._queue = queue.Queue()
        self._stop = threading.Event()
        self._threads = [threading.Thread(target=self._read_loop, name='pyrules-reader'),
                         threading.Thread(target=self._write_loop, name='pyrules-writer')]

    def start(self):
        while not self.link.ensure_open():
            if self._stop.wait(0.05):
                return
        self._request_topics()
        self.lastsync = self.clock()
        for thread in self._threads:
            thread.daemon = True
            thread.start()

    def stop(self):
        self._stop.set()
        for thread in self._threads:
            if thread.is_alive():
                thread.join(2.0)
        self.link.close()

    def publish(self, name, payload):
        """A ROS message on ``name`` (serialised): queued if the device subscribes."""
        topic_id = self.subscriber_ids.get(name)
        if topic_id is not None:
            self._queue.put((topic_id, bytes(payload)))

    def _request_topics(self):
        self.topic_requests += 1
        self.parser.reset()          # SerialClient flushes its input here
        self._queue.put((protocol.ID_PUBLISHER, b''))

    def _read_loop(self):
        while not self._stop.is_set():
            if self.clock() - self.lastsync > LASTSYNC_S:
                self.lost_syncs += 1
                self._request_topics()
                self.lastsync = self.clock()
            data = self.link.read()
            if data is None:
                if self._stop.wait(0.05):
                    return
                self.link.ensure_open()
                continue
            for frame in self.parser.feed(data):
                self._on_frame(frame)

    def _on_frame(self, frame):
        topic, payload = frame.topic, frame.payload
        if topic in (protocol.ID_PUBLISHER, protocol.ID_SUBSCRIBER):
            info = messages.decode_topic_info(payload)
            if topic == protocol.ID_PUBLISHER:
                self.publisher_names[info.topic_id] = info.topic_name
            else:
                self.subscriber_ids.setdefault(info.topic_name, info.topic_id)
                if self.buffer_in < 0:
                    self.buffer_in = info.buffer_size
        elif topic == protocol.ID_TIME:
            now = time.time()
            self._queue.put((protocol.ID_TIME, messages.encode_time(
                *messages.time_from_seconds(now))))
            self.lastsync = self.clock()
        elif topic == protocol.ID_LOG:
            self.logs.append(messages.decode_log(payload))
        elif topic in self.publisher_names:
            self.received.append((self.clock(), self.publisher_names[topic], payload))
        elif topic not in (protocol.ID_PARAMETER_REQUEST, protocol.ID_TX_STOP):
            self._request_topics()   # "Tried to publish before configured"

    def _write_loop(self):
        while not self._stop.is_set():
            try:
                topic_id, payload = self._queue.get_nowait()
            except queue.Empty:
                time.sleep(WRITE_IDLE_S)
                continue
            if topic_id >= protocol.FIRST_USER_TOPIC and 0 < self.buffer_in < len(payload):
                continue             # "message larger than buffer": dropped
            self.link.write(protocol.encode(topic_id, payload))


def serialise(msg):
    """Bytes of a genpy message, as a ROS subscriber callback would produce."""
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()
