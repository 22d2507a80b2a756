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

As rosserial_python does, TopicInfo (publishers, subscribers, both halves
of service servers and clients) is taken at any time, also while up: a
device that was reset announces itself again and the link stays up. A
frame on a topic id nobody announced means the device forgot its topics:
request them again (rosserial_python: "Tried to publish before configured").

Lost sync: no valid frame from the device for :meth:`HostSession.lost_after`
seconds while up and while the device waits for nothing. That limit comes
from what the device sent: three times the longest of its last
:data:`GAPS_KEPT` gaps between frames (messages and time requests; not the
burst of TopicInfo at setup, nor a gap spent waiting), never below
``sync_timeout`` (0.5 s: a device streaming at 90 Hz is found dead within
0.5 s) and never above :data:`LOST_AFTER_MAX_S`; until enough gaps were
seen it is :data:`LOST_AFTER_UNKNOWN_S`, so a ros_lib device that only
syncs every 2.5 s is never declared lost between its syncs.

A ros_lib device blocked in a request sends nothing of its own: in a
ServiceClient call, in a getParam, or in its ServiceServer's callback for a
request the host forwarded. Each such *wait* holds the link as long as
rosserial_python would keep it (see :data:`WAITS`); silence is counted
again from the moment the host answers (:meth:`HostSession.sent`) or gives
up (:meth:`HostSession.given_up`), and a wait ends too when the device
publishes on one of its topics (its loop runs again: ros_lib gave up).
"""
import collections

from pirate.link import messages, protocol

DOWN, NEGOTIATING, UP = 'down', 'negotiating', 'up'

GAPS_KEPT = 16
GAPS_NEEDED = 8               # gaps seen since up before the measured limit applies
GAP_FACTOR = 3.0
LOST_AFTER_UNKNOWN_S = 7.5    # 3 x ros_lib's 2.5 s time sync
LOST_AFTER_MAX_S = 15.0       # rosserial_python's 3 x 5 s

#: How long a device's wait holds the link, by what it waits for (s; None:
#: until answered). rosserial_python calls the ROS service of a device's
#: ServiceClient in its reader, which checks for lost sync only after the
#: call returned; it answers a parameter at once or never, and waits for a
#: device's ServiceServer forever, but either way it renegotiates once no
#: time request came for 3 x 5 s.
WAITS = {'client': None, 'param': LOST_AFTER_MAX_S, 'server': LOST_AFTER_MAX_S}

#: TopicInfo topics of the two halves of a device's service server/client:
#: frame topic id -> (service kind, the direction the device uses it in).
SERVICE_INFO = {
    protocol.ID_SERVICE_SERVER + protocol.ID_PUBLISHER: ('server', 'response'),
    protocol.ID_SERVICE_SERVER + protocol.ID_SUBSCRIBER: ('server', 'request'),
    protocol.ID_SERVICE_CLIENT + protocol.ID_PUBLISHER: ('client', 'request'),
    protocol.ID_SERVICE_CLIENT + protocol.ID_SUBSCRIBER: ('client', 'response'),
}

#: Something the session wants its owner to do. ``kind`` is one of
#: 'publisher', 'subscriber' (data: TopicInfo), 'service' (data: (kind,
#: part, TopicInfo)), 'message' (data: (topic id, payload)), 'service_frame'
#: (data: (topic id, payload)), 'log' (data: (level, text)), 'param' (data:
#: name; the owner answers with :meth:`HostSession.param_reply`), 'link'
#: (data: new state), 'lost_sync' (data: (running count, text)), 'error'
#: (data: text, to be logged once per text).
Event = collections.namedtuple('Event', 'kind data')


class HostSession(object):
    """What to send and what happened, frame by frame; see module docstring."""

    def __init__(self, sync_timeout=0.5, request_interval=1.0):
        self.sync_timeout = sync_timeout
        self.request_interval = request_interval
        self.state = DOWN
        self.publishers = {}      # device topic id -> TopicInfo (device publishes)
        self.subscribers = {}     # device topic id -> TopicInfo (device subscribes)
        self.services = {}        # device topic id -> (kind, part, TopicInfo)
        self.lost_syncs = 0
        self.time_requests = 0
        self._gaps = collections.deque(maxlen=GAPS_KEPT)
        self._gaps_since_up = 0
        self._quiet_since = None      # last frame from the device, or end of its wait
        self._last_data_rx = None
        self._waits = {}              # (kind, service name or '') -> deadline or None
        self._waited = False          # a wait since the last data frame: gap not measured
        self._last_request = None
        self._time_answered = False

    # -- link ---------------------------------------------------------------
    def opened(self, now):
        """The port was (re)opened: return the bytes that start negotiation."""
        self._quiet_since = now
        return self._request(now)

    def closed(self):
        """The port was lost; return events (link state)."""
        return self._set_state(DOWN)

    def _request(self, now):
        """Forget the device's topics and ask it to announce them again."""
        self.publishers.clear()
        self.subscribers.clear()
        self.services.clear()
        self._waits.clear()
        self._time_answered = False
        self._last_request = now
        self.state = NEGOTIATING
        return protocol.encode(protocol.ID_PUBLISHER)

    def _set_state(self, state):
        if state == self.state:
            return []
        self.state = state
        if state == UP:
            self._gaps.clear()          # what negotiation took says nothing of the stream
            self._gaps_since_up = 0
        return [Event('link', state)]

    def tx_stop(self):
        """Bytes telling the device we are going away (rosserial ID_TX_STOP)."""
        return protocol.encode(protocol.ID_TX_STOP)

    # -- time ---------------------------------------------------------------
    def lost_after(self):
        """Seconds of device silence that count as lost sync (module docstring)."""
        if self._gaps_since_up < GAPS_NEEDED:
            return max(self.sync_timeout, LOST_AFTER_UNKNOWN_S)
        return min(max(self.sync_timeout, GAP_FACTOR * max(self._gaps)), LOST_AFTER_MAX_S)

    def tick(self, now):
        """Periodic check; return (bytes to send, events)."""
        if self.state == DOWN:
            return b'', []
        limit = self.lost_after()
        if self.state == UP and not self.device_waits(now) and now - self._quiet_since > limit:
            return self._lost_sync(now, 'no frame from the device for %.1f s' % limit)
        if self.state == NEGOTIATING and now - self._last_request >= self.request_interval:
            return self._request(now), []
        return b'', []

    def _lost_sync(self, now, why):
        self.lost_syncs += 1
        return self._request(now), [
            Event('lost_sync', (self.lost_syncs, '%s, requesting topics again' % why)),
            Event('link', NEGOTIATING)]

    # -- the device's waits -------------------------------------------------
    def device_waits(self, now):
        """What the device waits for at ``now``: [(kind, service name or '')];
        a wait past its deadline (:data:`WAITS`) is dropped."""
        for key, deadline in list(self._waits.items()):
            if deadline is not None and now > deadline:
                self._waits.pop(key, None)     # the diagnostics thread may ask too
        return sorted(self._waits)

    def _wait(self, kind, name, now):
        limit = WAITS[kind]
        self._waits[(kind, name)] = None if limit is None else now + limit
        self._waited = True

    def _end_wait(self, kind, name, now):
        if self._waits.pop((kind, name), False) is not False:
            self._quiet_since = max(self._quiet_since, now)

    def sent(self, topic, now):
        """The owner wrote a frame on ``topic`` to the device: an answer to a
        parameter or to the device's ServiceClient ends that wait; a request
        to the device's ServiceServer starts one."""
        if topic == protocol.ID_PARAMETER_REQUEST:
            self._end_wait('param', '', now)
        elif topic in self.services:
            kind, part, info = self.services[topic]
            if (kind, part) == ('client', 'response'):
                self._end_wait('client', info.topic_name, now)
            elif (kind, part) == ('server', 'request'):
                self._wait('server', info.topic_name, now)

    def given_up(self, kind, name, now):
        """The owner will not answer the device's ``kind`` ('client', 'param')
        wait on ``name``, or stopped waiting for its 'server' ``name``."""
        self._end_wait(kind, name, now)

    # -- frames -------------------------------------------------------------
    def on_frame(self, frame, now, host_time):
        """Handle one frame from the device; return (bytes to send, events).

        ``host_time`` is the time (s, float) to answer a time request with.
        """
        self._quiet_since = now
        topic = frame.topic
        if topic in (protocol.ID_PUBLISHER, protocol.ID_SUBSCRIBER) or topic in SERVICE_INFO:
            return self._topic_info(frame)   # a burst at setup: says nothing of the stream
        if self._last_data_rx is not None and not self._waited:
            self._gaps.append(max(0.0, now - self._last_data_rx))
            self._gaps_since_up += 1
        self._last_data_rx = now
        self._waited = bool(self._waits)
        if topic == protocol.ID_TIME:
            self.time_requests += 1
            self._time_answered = True
            reply = protocol.encode(protocol.ID_TIME,
                                    messages.encode_time(*messages.time_from_seconds(host_time)))
            return reply, self._maybe_up()
        if topic == protocol.ID_LOG:
            return b'', [self._decoded('log', messages.decode_log, frame.payload)]
        if topic == protocol.ID_PARAMETER_REQUEST:
            self._wait('param', '', now)
            return b'', [self._decoded('param', messages.decode_param_request, frame.payload)]
        if topic == protocol.ID_TX_STOP:
            return b'', []
        if topic in self.publishers:
            self._waits.clear()          # the device runs its loop again
            return b'', [Event('message', (topic, frame.payload))]
        if topic in self.services:
            self._service_frame(topic, now)
            return b'', [Event('service_frame', (topic, frame.payload))]
        if self.state == UP:
            return self._lost_sync(now, 'frame on unknown topic id %d: the device forgot '
                                        'its topics' % topic)
        return b'', []

    def _service_frame(self, topic, now):
        kind, part, info = self.services[topic]
        if (kind, part) == ('client', 'request'):
            self._wait('client', info.topic_name, now)
        elif (kind, part) == ('server', 'response'):
            self._end_wait('server', info.topic_name, now)

    @staticmethod
    def _decoded(kind, decode, payload):
        try:
            return Event(kind, decode(payload))
        except messages.DecodeError as error:
            return Event('error', 'bad %s frame from device: %s' % (kind, error))

    @staticmethod
    def param_reply(value):
        """Bytes answering a parameter request with ``value`` (ints/bools, floats
        or strings, alone or as a list of one type), as rosserial_python does;
        ValueError (with the reason) for what ros_lib cannot receive."""
        return protocol.encode(protocol.ID_PARAMETER_REQUEST,
                               messages.encode_param_value(value))

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
        if frame.topic in SERVICE_INFO:
            kind, part = SERVICE_INFO[frame.topic]
            self.services[info.topic_id] = (kind, part, info)
            event = Event('service', (kind, part, info))
        else:
            publishes = frame.topic == protocol.ID_PUBLISHER
            (self.publishers if publishes else self.subscribers)[info.topic_id] = info
            event = Event('publisher' if publishes else 'subscriber', info)
        return b'', [event] + self._maybe_up()

    def _maybe_up(self):
        if (self.state == NEGOTIATING and self._time_answered
                and (self.publishers or self.subscribers or self.services)):
            return self._set_state(UP)
        return []

    def subscriber(self, topic_name):
        """TopicInfo of the device's subscriber to ``topic_name``, or None."""
        for info in self.subscribers.values():
            if info.topic_name == topic_name:
                return info
        return None

    def buffer_size(self, topic_id):
        """Bytes the device announced it can receive on ``topic_id`` (0: unknown)."""
        if topic_id in self.subscribers:
            return self.subscribers[topic_id].buffer_size
        if topic_id in self.services:
            return self.services[topic_id][2].buffer_size
        return 0

    def max_publish_size(self):
        """Largest payload the device announced it may send (its buffer)."""
        sizes = [i.buffer_size for i in self.publishers.values()]
        sizes += [i.buffer_size for k, p, i in self.services.values()]
        return max(sizes + [protocol.DEFAULT_MAX_PAYLOAD])
