"""ROS services to and from a rosserial device (the host's side; ROS edge).

A device's ServiceServer becomes a ``rospy.Service``: a ROS call is sent to
the device as the request and waits (at most ``timeout`` s: rosserial_python
waits forever, but renegotiates after 15 s without a time request, which a
device in its callback does not send) for the device's response frame. A device's ServiceClient
becomes a ``rospy.ServiceProxy``: the device's request frames are called on
a worker thread (never the port reader: a slow service must not stall the
link) and the response goes back to the device.

Each service has two halves announced separately (session.SERVICE_INFO);
the bridge is created on the first and checks each half's md5.
"""
import io
import queue
import threading

import rospy
import roslib.message

from pirate.link.session import LOST_AFTER_MAX_S


class ServiceBridge(object):
    """All services of one device. ``send(topic_id, payload)`` writes a frame
    (False if the link is not up); ``warn(text)`` logs a problem once;
    ``given_up(kind, name)`` says a device's call of ``name`` gets no answer
    ('client') or the device's answer is no longer awaited ('server')."""

    def __init__(self, send, warn, given_up, timeout=LOST_AFTER_MAX_S):
        self._send = send
        self._warn = warn
        self._given_up = given_up
        self.timeout = timeout
        self._servers = {}     # name -> _Server
        self._clients = {}     # name -> rospy.ServiceProxy
        self._ids = {}         # (kind, part, name) -> device topic id
        self._requests = queue.Queue()
        self._worker = threading.Thread(target=self._call_loop, name='rosserial-services')
        self._worker.daemon = True
        self._worker.start()

    def announce(self, kind, part, info):
        """A device announced one half of a service (see session.SERVICE_INFO)."""
        srv = roslib.message.get_service_class(info.message_type)
        if srv is None or not hasattr(srv, '_request_class'):
            self._warn('device service %s has unknown type %s' % (info.topic_name,
                                                                   info.message_type))
            return
        half = srv._request_class if part == 'request' else srv._response_class
        if half._md5sum != info.md5sum:
            self._warn('device service %s: %s md5 %s does not match ours (%s); ignored'
                       % (info.topic_name, part, info.md5sum, half._md5sum))
            return
        self._ids[(kind, part, info.topic_name)] = info.topic_id
        if kind == 'server' and info.topic_name not in self._servers:
            rospy.loginfo('device serves %s [%s]', info.topic_name, info.message_type)
            self._servers[info.topic_name] = _Server(self, info.topic_name, srv)
        elif kind == 'client' and info.topic_name not in self._clients:
            rospy.loginfo('device calls %s [%s]', info.topic_name, info.message_type)
            self._clients[info.topic_name] = rospy.ServiceProxy(info.topic_name, srv)

    def on_frame(self, kind, part, info, payload):
        """A frame from the device on one half of a service."""
        if kind == 'server' and info.topic_name in self._servers:
            self._servers[info.topic_name].response(payload)
        elif kind == 'client' and info.topic_name in self._clients:
            self._requests.put((info.topic_name, payload))

    def send_to_device(self, kind, part, name, msg):
        """Serialise ``msg`` onto the device's half (kind, part) of ``name``."""
        topic_id = self._ids.get((kind, part, name))
        buff = io.BytesIO()
        msg.serialize(buff)
        return topic_id is not None and self._send(topic_id, buff.getvalue())

    def _call_loop(self):
        while not rospy.is_shutdown():
            try:
                name, payload = self._requests.get(timeout=0.5)
            except queue.Empty:
                continue
            proxy = self._clients[name]
            request = proxy.request_class()
            try:
                request.deserialize(payload)
                response = proxy(request)
            except Exception as error:  # genpy and rospy raise several types
                self._warn('device call of %s failed: %s' % (name, error))
                self._given_up('client', name)
                continue
            self.send_to_device('client', 'response', name, response)


class _Server(object):
    """One device ServiceServer as a rospy.Service; one call at a time."""

    def __init__(self, bridge, name, srv):
        self._bridge = bridge
        self._name = name
        self._srv = srv
        self._lock = threading.Lock()
        self._done = threading.Event()
        self._payload = None
        self.service = rospy.Service(name, srv, self._call)

    def _call(self, request):
        with self._lock:
            self._done.clear()
            if not self._bridge.send_to_device('server', 'request', self._name, request):
                raise rospy.ServiceException('device link is not up')
            if not self._done.wait(self._bridge.timeout):
                self._bridge._given_up('server', self._name)
                raise rospy.ServiceException('device did not answer %s within %.1f s'
                                             % (self._name, self._bridge.timeout))
            response = self._srv._response_class()
            response.deserialize(self._payload)
            return response

    def response(self, payload):
        self._payload = payload
        self._done.set()
