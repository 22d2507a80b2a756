"""The host's ROS edge without a master or a port: buffer sizes refused,
renegotiated types recreated, parameters served, the laptop's latched state re-sent, version mismatch on
diagnostics. The port is a fake that records what was written."""
import struct

import pytest
from diagnostic_msgs.msg import DiagnosticStatus
from std_msgs.msg import Int16, String

from pirate.link import host_ros as host_module
from pirate.link import messages, protocol, session
from pirate.link.protocol import Frame, FrameParser


class FakeLink(object):
    port_name = '/dev/fake'
    baud = 57600
    is_open = True
    bytes_in = bytes_out = 0
    last_error = None

    def __init__(self):
        self.written = []

    def write(self, data):
        if data:
            self.written.extend(FrameParser().feed(data))
        return True

    def discard_output(self):
        del self.written[:]          # what the port had not sent yet


class Announcements(object):
    def __init__(self):
        self.count = 0

    def publish(self, _msg):
        self.count += 1


@pytest.fixture
def host():
    h = host_module.RosserialHost('/dev/fake', 57600)
    h.link = FakeLink()
    h._announced = Announcements()      # no master to publish to
    h.session.opened(0.0)
    yield h
    for sub in h._subscribers.values():
        sub.unregister()
    for _, pub in h._publishers.values():
        pub.unregister()


def announce(h, kind, topic_id, name, cls, size=64):
    info = messages.TopicInfo(topic_id, name, cls._type, cls._md5sum, size)
    _, events = h.session.on_frame(Frame(kind, messages.encode_topic_info(info)), 0.0, 0)
    h._handle(events)


def up(h):
    reply, events = h.session.on_frame(Frame(protocol.ID_TIME, bytes(8)), 0.0, 1.0)
    h._handle(events)
    assert h.session.state == session.UP


def test_message_larger_than_the_device_buffer_is_refused(host):
    announce(host, protocol.ID_SUBSCRIBER, 101, '/text', String, size=16)
    up(host)
    assert not host._send_frame(101, bytes(17), '/text')
    assert host.counts['oversize_refused'] == 1
    assert host._send_frame(101, bytes(16), '/text')
    assert host.link.written[-1] == Frame(101, bytes(16))


def test_a_message_larger_than_the_buffer_is_an_error(host, monkeypatch):
    logged = []
    for level in ('logwarn', 'logerr'):
        monkeypatch.setattr(host_module.rospy, level,
                            lambda *args, level=level: logged.append((level, args[0] % args[1:])))
    announce(host, protocol.ID_SUBSCRIBER, 101, '/text', String, size=16)
    up(host)
    host._send_frame(101, bytes(17), '/text')
    assert [level for level, _ in logged] == ['logerr']
    assert 'message larger than buffer' in logged[0][1] and '/text' in logged[0][1]


class FakeUpdater(object):
    def __init__(self):
        self.forced = 0

    def force_update(self):
        self.forced += 1


def test_every_lost_sync_is_a_warning_with_its_count_and_on_diagnostics(host, monkeypatch):
    warned = []
    monkeypatch.setattr(host_module.rospy, 'logwarn', lambda *args: warned.append(args[0] % args[1:]))
    host._updater = FakeUpdater()
    announce(host, protocol.ID_PUBLISHER, 100, '/chatter', String)
    t = 0.0
    for episode in range(5):
        host._carry_out(*host.session.on_frame(Frame(protocol.ID_TIME, bytes(8)), t, 1.0))
        for _ in range(10):                      # streaming at 100 Hz
            t += 0.01
            host._carry_out(*host.session.on_frame(Frame(100, b'\x00\x00\x00\x00'), t, 1.0))
        host._carry_out(*host.session.tick(t + 8.0))         # then silent: lost
        # the topic request survives the discarding of what was queued for the device
        assert host.link.written == [Frame(protocol.ID_PUBLISHER, b'')]
        announce(host, protocol.ID_PUBLISHER, 100, '/chatter', String)
        t += 8.0
    lost = [text for text in warned if 'lost sync' in text]
    assert ['(%d so far)' % n in text for n, text in zip(range(1, 6), lost)] == [True] * 5
    assert host._updater.forced == 5
    status = host.diagnostic_status()
    assert 'lost sync 5 times' in status.message
    values = {pair.key: pair.value for pair in status.values}
    assert values['lost_syncs'] == '5' and values['last_lost_sync'].startswith('#5 ')


def test_frames_up_to_the_largest_announced_buffer_are_taken(host):
    # frames over 512 bytes must not be dropped when the device announced more
    announce(host, protocol.ID_PUBLISHER, 100, '/big', String, size=2048)
    payload = struct.pack('<I', 1500) + b'x' * 1500
    assert host.parser.feed(protocol.encode(100, payload)) == [Frame(100, payload)]


def test_a_topic_renegotiated_with_another_type_is_recreated(host):
    announce(host, protocol.ID_SUBSCRIBER, 101, '/cmd', Int16)
    announce(host, protocol.ID_PUBLISHER, 100, '/out', Int16)
    first_sub, first_pub = host._subscribers['/cmd'], host._publishers['/out'][1]
    announce(host, protocol.ID_SUBSCRIBER, 101, '/cmd', String)
    announce(host, protocol.ID_PUBLISHER, 100, '/out', String)
    assert host._subscribers['/cmd'].data_class is String
    assert host._publishers['/out'][0] is String
    assert first_sub is not host._subscribers['/cmd'] and first_pub.impl is None


def test_parameters_served_from_the_parameter_server(host, monkeypatch):
    params = {'~gain': 7, '~bad': {'a': 1}}
    monkeypatch.setattr(host_module.rospy, 'get_param', lambda name: params[name])
    monkeypatch.setattr(host_module.rospy, 'logerr', lambda *args: None)
    for name in ('~gain', '~missing', '~bad'):
        request = Frame(protocol.ID_PARAMETER_REQUEST, struct.pack('<I', len(name)) + name.encode())
        host._handle(host.session.on_frame(request, 0.0, 0)[1])
    assert host.link.written == [Frame(protocol.ID_PARAMETER_REQUEST,
                                       messages.encode_param_response(ints=[7]))]
    assert host.counts['params_served'] == 1


def test_latched_state_is_resent_on_link_up_and_on_reannouncement(host):
    announce(host, protocol.ID_SUBSCRIBER, 102, '/control', Int16)
    latched, streamed = Int16(data=3), Int16(data=4)
    latched._connection_header = {'latching': '1'}
    host._forward('/control', latched)
    host._forward('/control', streamed)          # not latched: not state
    host.outbox.clear()                          # the link was not up: nothing sent
    up(host)
    assert [p for _, p in host.outbox.take(host._clock())] == [b'\x03\x00']
    announce(host, protocol.ID_SUBSCRIBER, 102, '/control', Int16)   # device reset
    assert [p for _, p in host.outbox.take(host._clock())] == [b'\x03\x00']


def test_the_device_announcing_itself_is_said_on_link_up_and_after_a_reset(host):
    said = host._announced
    announce(host, protocol.ID_SUBSCRIBER, 102, '/control', Int16)
    assert said.count == 0                       # negotiating: not up yet
    up(host)
    assert said.count == 1
    announce(host, protocol.ID_SUBSCRIBER, 102, '/control', Int16)   # device reset
    assert said.count == 2


def test_version_mismatch_is_an_error_on_diagnostics(host, monkeypatch):
    errors = []
    monkeypatch.setattr(host_module.rospy, 'logerr', lambda *args: errors.append(args))
    host.parser.feed(bytes([0xFF, 0xFD, 0, 0, 0xFF, 0, 0, 0xFF]))
    host._check_version()
    host._check_version()
    assert len(errors) == 1 and 'Mismatched protocol version' in errors[0][0] % errors[0][1:]
    status = host.diagnostic_status()
    assert status.level == DiagnosticStatus.ERROR
    assert status.message.startswith('Mismatched protocol version')


def test_a_bad_service_announcement_is_refused_and_the_reader_lives(host, monkeypatch):
    warned = []
    monkeypatch.setattr(host, '_warn', warned.append)
    monkeypatch.setattr(host.services, '_warn', warned.append)
    # a message type where a service type belongs: refused with a reason
    announce(host, 2, 120, '/not_a_service', String)
    assert warned and 'unknown type std_msgs/String' in warned[0]
    # whatever a handler raises becomes a warning, never an exception in the reader
    monkeypatch.setattr(host.services, 'announce', lambda *a: 1 / 0)
    announce(host, 2, 121, '/boom', String)
    assert 'ZeroDivisionError' in warned[-1]
