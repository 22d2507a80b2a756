"""The host's side of a rosserial session: negotiation, time sync, lost sync.

A pure state machine (no port, no ROS, time passed in), the part of
rosserial_python's SerialClient that decides *what* to say; :mod:`.host`
does the talking. Link states:

- ``down``         no port open;
- ``negotiating``  topics requested, waiting for the device's TopicInfo and
                   time request; requests are repeated every
                   ``request_interval`` s (a Mega reset by the port opening
                   needs about 1-2 s in its bootloader before it listens);
- ``up``           the device announced its topics and we answered a time
                   request since our last topic request: the handshake is
                   done and commands may flow.

Lost sync: no valid frame from the device for ``sync_timeout`` s while up, or
a frame on a topic id we do not know (the device was reset behind our back),
sends the link back to ``negotiating``.
"""
import collections

from pirate.link import messages, protocol

DOWN, NEGOTIATING, UP = 'down', 'negotiating', 'up'

#: Something the session wants its owner to do. ``kind`` is one of
#: 'publisher', 'subscriber' (data: TopicInfo), 'message' (data: (topic id,
#: payload)), 'log' (data: (level, text)), 'link' (data: new state),
#: 'error' (data: text, to be logged once per distinct text).
Event = collections.namedtuple('Event', 'kind data')


class HostSession(object):
    """What to send and what happened, frame by frame; see module docstring."""

    def __init__(self, sync_timeout=3.0, request_interval=1.0):
        self.sync_timeout = sync_timeout
        self.request_interval = request_interval
        self.state = DOWN
        self.publishers = {}      # device topic id -> TopicInfo (device publishes)
        self.subscribers = {}     # device topic id -> TopicInfo (device subscribes)
        self.lost_syncs = 0
        self.time_requests = 0
        self._last_rx = None
        self._last_request = None
        self._time_answered = False

    # -- link ---------------------------------------------------------------
    def opened(self, now):
        """The port was (re)opened: return the bytes that start negotiation."""
        self._last_rx = now
        return self._request(now)

    def closed(self):
        """The port was lost; return events (link state)."""
        return self._set_state(DOWN)

    def _request(self, now):
        """Forget the device's topics and ask it to announce them again."""
        self.publishers.clear()
        self.subscribers.clear()
        self._time_answered = False
        self._last_request = now
        self.state = NEGOTIATING
        return protocol.encode(protocol.ID_PUBLISHER)

    def _set_state(self, state):
        if state == self.state:
            return []
        self.state = state
        return [Event('link', state)]

    def tx_stop(self):
        """Bytes telling the device we are going away (rosserial ID_TX_STOP)."""
        return protocol.encode(protocol.ID_TX_STOP)

    # -- time ---------------------------------------------------------------
    def tick(self, now):
        """Periodic check; return (bytes to send, events)."""
        if self.state == DOWN:
            return b'', []
        if self.state == UP and now - self._last_rx > self.sync_timeout:
            self.lost_syncs += 1
            events = [Event('error', 'lost sync with the device (no frame for %.1f s), '
                                     'requesting topics again' % self.sync_timeout),
                      Event('link', NEGOTIATING)]
            return self._request(now), events
        if self.state == NEGOTIATING and now - self._last_request >= self.request_interval:
            return self._request(now), []
        return b'', []

    # -- frames -------------------------------------------------------------
    def on_frame(self, frame, now, host_time):
        """Handle one frame from the device; return (bytes to send, events).

        ``host_time`` is the time (s, float) to answer a time request with.
        """
        self._last_rx = now
        topic = frame.topic
        if topic in (protocol.ID_PUBLISHER, protocol.ID_SUBSCRIBER):
            return self._topic_info(frame)
        if topic == protocol.ID_TIME:
            self.time_requests += 1
            self._time_answered = True
            reply = protocol.encode(protocol.ID_TIME,
                                    messages.encode_time(*messages.time_from_seconds(host_time)))
            return reply, self._maybe_up()
        if topic == protocol.ID_LOG:
            try:
                return b'', [Event('log', messages.decode_log(frame.payload))]
            except messages.DecodeError as error:
                return b'', [Event('error', 'bad Log frame from device: %s' % error)]
        if topic == protocol.ID_PARAMETER_REQUEST:
            # We serve no parameters: answer empty so the device does not wait.
            return protocol.encode(protocol.ID_PARAMETER_REQUEST,
                                   messages.encode_param_response()), []
        if topic == protocol.ID_TX_STOP:
            return b'', []
        if topic in self.publishers:
            return b'', [Event('message', (topic, frame.payload))]
        if self.state == UP:
            self.lost_syncs += 1
            return self._request(now), [
                Event('error', 'frame on unknown topic id %d: device was reset, '
                               'requesting topics again' % topic),
                Event('link', NEGOTIATING)]
        return b'', []

    def _topic_info(self, frame):
        if not frame.payload:
            return b'', []
        try:
            info = messages.decode_topic_info(frame.payload)
        except messages.DecodeError as error:
            return b'', [Event('error', 'bad TopicInfo from device: %s' % error)]
        if info.topic_id < protocol.FIRST_USER_TOPIC:
            return b'', [Event('error', 'device announced reserved topic id %d for %s'
                                        % (info.topic_id, info.topic_name))]
        table = self.publishers if frame.topic == protocol.ID_PUBLISHER else self.subscribers
        table[info.topic_id] = info
        kind = 'publisher' if frame.topic == protocol.ID_PUBLISHER else 'subscriber'
        return b'', [Event(kind, info)] + self._maybe_up()

    def _maybe_up(self):
        if (self.state == NEGOTIATING and self._time_answered
                and (self.publishers or self.subscribers)):
            return self._set_state(UP)
        return []

    def subscriber_id(self, topic_name):
        """Device topic id of the device's subscriber to ``topic_name``, or None."""
        for topic_id, info in self.subscribers.items():
            if info.topic_name == topic_name:
                return topic_id
        return None
