"""Codec unit tests: frames written out byte by byte from the rosserial
protocol description (wiki.ros.org/rosserial/Overview/Protocol), the
protocol's own payloads, the host session and the outbox. No ROS master."""
import struct

import pytest

from pirate.link import messages, protocol, session
from pirate.link.outbox import Outbox
from pirate.link.protocol import Frame, FrameParser

# The host's topic request: topic 0, empty payload (rosserial_python sends it).
TOPIC_REQUEST = bytes([0xFF, 0xFE, 0x00, 0x00, 0xFF, 0x00, 0x00, 0xFF])
# ID_TX_STOP (11): message checksum 255 - 11 = 0xF4.
TX_STOP = bytes([0xFF, 0xFE, 0x00, 0x00, 0xFF, 0x0B, 0x00, 0xF4])
# Time reply secs=1 nsecs=2 on ID_TIME (10): len 8 -> len chk 0xF7,
# msg chk 255 - (10 + 1 + 2) = 0xF2.
TIME_1_2 = bytes([0xFF, 0xFE, 0x08, 0x00, 0xF7, 0x0A, 0x00,
                  0x01, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0xF2])
# SetpointArray (int16[13], fixed size: 26 bytes, no length prefix) on topic
# 100 with data[0] = 1: len chk 255 - 26 = 0xE5, msg chk 255 - (100 + 1) = 0x9A.
SETPOINT_FRAME = (bytes([0xFF, 0xFE, 0x1A, 0x00, 0xE5, 0x64, 0x00, 0x01, 0x00])
                  + bytes(24) + bytes([0x9A]))


def test_known_frames_encode_byte_for_byte():
    assert protocol.encode(protocol.ID_PUBLISHER) == TOPIC_REQUEST
    assert protocol.encode(protocol.ID_TX_STOP) == TX_STOP
    assert protocol.encode(protocol.ID_TIME, messages.encode_time(1, 2)) == TIME_1_2
    assert protocol.encode(100, struct.pack('<13h', 1, *[0] * 12)) == SETPOINT_FRAME


@pytest.mark.parametrize('raw,topic', [(TOPIC_REQUEST, 0), (TX_STOP, 11),
                                       (TIME_1_2, 10), (SETPOINT_FRAME, 100)])
def test_known_frames_decode(raw, topic):
    frames = FrameParser().feed(raw)
    assert [f.topic for f in frames] == [topic]
    assert frames[0].payload == raw[7:-1]


def test_checksums_of_long_length_wrap():
    # len 0x0102: 255 - (2 + 1) = 252
    assert protocol.length_checksum(0x0102) == 252
    assert protocol.message_checksum(0x0165, b'\xff\xff') == 255 - ((0x65 + 1 + 510) % 256)


def test_byte_at_a_time_equals_whole():
    stream = TOPIC_REQUEST + SETPOINT_FRAME + TIME_1_2
    parser = FrameParser()
    one_by_one = [f for b in stream for f in parser.feed(bytes([b]))]
    assert one_by_one == FrameParser().feed(stream)
    assert len(one_by_one) == 3


def test_bad_message_checksum_is_dropped_and_counted():
    bad = bytearray(SETPOINT_FRAME)
    bad[-1] ^= 0x01
    parser = FrameParser()
    assert parser.feed(bytes(bad)) == []
    assert parser.stats.checksum_errors == 1
    assert parser.feed(SETPOINT_FRAME) == [Frame(100, SETPOINT_FRAME[7:-1])]


def test_bad_length_checksum_resyncs_to_next_frame():
    bad = bytearray(TIME_1_2)
    bad[4] ^= 0x10
    parser = FrameParser()
    frames = parser.feed(bytes(bad) + TX_STOP)
    assert frames == [Frame(11, b'')]
    assert parser.stats.length_errors == 1
    assert parser.resyncs >= 1


def test_frame_inside_truncated_frame_is_found():
    # a header promising 26 bytes, cut off after 3, then whole frames: the
    # parser waits for 26 bytes, the checksum fails, it rescans inside them
    stream = SETPOINT_FRAME[:10] + TIME_1_2 + TX_STOP
    assert FrameParser().feed(stream) == [Frame(10, TIME_1_2[7:-1]), Frame(11, b'')]


def test_wrong_protocol_version_is_rejected():
    groovy = bytes([0xFF, 0xFF]) + TOPIC_REQUEST[2:]   # pre-Hydro version byte
    parser = FrameParser()
    assert parser.feed(groovy) == []
    assert parser.feed(TOPIC_REQUEST) == [Frame(0, b'')]


def test_oversize_length_is_garbage():
    parser = FrameParser(max_payload=16)
    assert parser.feed(SETPOINT_FRAME + TX_STOP) == [Frame(11, b'')]
    assert parser.stats.oversize == 1


def test_encode_rejects_out_of_range():
    with pytest.raises(ValueError):
        protocol.encode(70000)


def test_topic_info_roundtrip_and_layout():
    info = messages.TopicInfo(101, '/pirate/Small_State', 'pirate/SmallState',
                              'abc', 280)
    raw = messages.encode_topic_info(info)
    assert raw[:2] == b'\x65\x00'
    assert raw[2:6] == struct.pack('<I', len('/pirate/Small_State'))
    assert raw[-4:] == struct.pack('<i', 280)
    assert messages.decode_topic_info(raw) == info
    with pytest.raises(messages.DecodeError):
        messages.decode_topic_info(raw[:-1])
    with pytest.raises(messages.DecodeError):
        messages.decode_topic_info(raw + b'\x00')


def test_time_and_log_and_params():
    assert messages.decode_time(messages.encode_time(7, 999)) == (7, 999)
    assert messages.time_from_seconds(3.9999999999) == (4, 0)
    log = struct.pack('<BI', 2, 5) + b'hello'
    assert messages.decode_log(log) == ('warn', 'hello')
    assert messages.decode_param_request(struct.pack('<I', 2) + b'ab') == 'ab'
    assert messages.encode_param_response() == bytes(12)


# -- session -----------------------------------------------------------------
def _info_frame(kind, topic_id, name):
    info = messages.TopicInfo(topic_id, name, 'pirate/SetpointArray', 'md5', 64)
    return Frame(kind, messages.encode_topic_info(info))


def _handshake(sess, now=0.0):
    assert sess.opened(now) == TOPIC_REQUEST
    sess.on_frame(_info_frame(protocol.ID_PUBLISHER, 100, '/pirate/Small_State'), now, 0)
    sess.on_frame(_info_frame(protocol.ID_SUBSCRIBER, 101, '/pirate/setpoint_array'), now, 0)
    reply, events = sess.on_frame(Frame(protocol.ID_TIME, b''), now, 12.5)
    return reply, events


def test_session_handshake_then_up():
    sess = session.HostSession()
    assert sess.state == session.DOWN
    reply, events = _handshake(sess)
    assert reply == protocol.encode(protocol.ID_TIME, messages.encode_time(12, 500000000))
    assert ('link', session.UP) in events
    assert sess.subscriber('/pirate/setpoint_array').topic_id == 101
    assert sess.subscriber('/nothing') is None
    assert sess.buffer_size(101) == 64 and sess.buffer_size(150) == 0


def test_session_not_up_without_time_request():
    sess = session.HostSession()
    sess.opened(0.0)
    sess.on_frame(_info_frame(protocol.ID_PUBLISHER, 100, '/a'), 0.0, 0)
    assert sess.state == session.NEGOTIATING
    # no answer: the request is repeated every request_interval
    assert sess.tick(0.5) == (b'', [])
    assert sess.tick(1.0)[0] == TOPIC_REQUEST


def _stream(sess, start, period, count):
    """The device sends a frame every ``period`` s; return the last time."""
    t = start
    for _ in range(count):
        t += period
        sess.on_frame(Frame(100, b'x'), t, 0)
    return t


def test_session_lost_sync_after_silence_of_a_streaming_device():
    sess = session.HostSession(sync_timeout=0.5)
    _handshake(sess)
    last = _stream(sess, 0.0, 0.011, 40)        # 90 frames/s
    assert sess.lost_after() == 0.5
    assert sess.tick(last + 0.45) == (b'', [])
    data, events = sess.tick(last + 0.55)
    assert data == TOPIC_REQUEST
    assert ('link', session.NEGOTIATING) in events
    assert sess.lost_syncs == 1 and not sess.subscribers


def test_session_does_not_flap_with_a_device_that_syncs_every_2_5_s():
    # a fixed 0.5 s timeout lost sync 107 times in 55 s with such a device
    sess = session.HostSession(sync_timeout=0.5)
    _handshake(sess)
    t = 0.0
    for _ in range(22):                          # 55 s of time requests only
        for step in range(25):
            assert sess.tick(t + step * 0.1)[1] == []
        t += 2.5
        sess.on_frame(Frame(protocol.ID_TIME, bytes(8)), t, 0)
    assert sess.lost_syncs == 0 and sess.state == session.UP
    assert 7.0 <= sess.lost_after() <= 15.0
    assert sess.tick(t + 7.6)[1][-1] == ('link', session.NEGOTIATING)


def _streaming_with_services(sess):
    """Up, streaming at 90 Hz, with a ServiceClient (122/123) and a
    ServiceServer (120/121) on the device; return the last frame's time."""
    _handshake(sess)
    for kind, topic_id in ((2, 120), (3, 121), (4, 122), (5, 123)):
        info = messages.TopicInfo(topic_id, '/srv%d' % (kind // 2), 'std_srvs/Trigger', 'md5', 300)
        sess.on_frame(Frame(kind, messages.encode_topic_info(info)), 0.0, 0)
    last = _stream(sess, 0.0, 0.011, 40)
    assert sess.lost_after() == 0.5
    return last


def _ticks(sess, start, end):
    """Lost-sync events of ticks every 10 ms from ``start`` to ``end`` (s)."""
    events, t = [], start
    while t < end:
        events += [e for e in sess.tick(t)[1] if e.kind == 'lost_sync']
        t += 0.01
    return events


def test_a_device_in_a_service_call_holds_the_link_until_answered():
    sess = session.HostSession(sync_timeout=0.5)
    last = _streaming_with_services(sess)
    sess.on_frame(Frame(122, b'request'), last, 0)            # ServiceClient::call
    assert sess.device_waits(last) == [('client', '/srv2')]
    assert _ticks(sess, last, last + 30.0) == []              # as long as the laptop takes
    sess.sent(123, last + 30.0)                               # the answer
    assert sess.device_waits(last + 30.0) == []
    assert _ticks(sess, last + 30.0, last + 30.45) == []
    (event,) = _ticks(sess, last + 30.45, last + 30.6)        # silent after it: dead
    assert event.data[0] == 1 and sess.state == session.NEGOTIATING


def test_the_wait_is_not_a_gap_of_the_stream():
    sess = session.HostSession(sync_timeout=0.5)
    last = _streaming_with_services(sess)
    sess.on_frame(Frame(122, b'request'), last, 0)
    sess.on_frame(Frame(protocol.ID_TIME, b''), last + 1.0, 0)   # spinOnce syncs meanwhile
    sess.sent(123, last + 1.5)
    last = _stream(sess, last + 1.5, 0.011, 20)
    assert sess.lost_after() == 0.5


def test_a_call_the_laptop_gives_up_lets_silence_count_again():
    sess = session.HostSession(sync_timeout=0.5)
    last = _streaming_with_services(sess)
    sess.on_frame(Frame(122, b'request'), last, 0)
    sess.given_up('client', '/srv2', last + 2.0)
    assert _ticks(sess, last, last + 2.45) == []
    assert len(_ticks(sess, last + 2.45, last + 2.6)) == 1


def test_a_missing_parameter_holds_the_link_until_the_device_runs_again():
    sess = session.HostSession(sync_timeout=0.5)
    last = _streaming_with_services(sess)
    sess.on_frame(Frame(protocol.ID_PARAMETER_REQUEST, struct.pack('<I', 2) + b'~x'), last, 0)
    assert _ticks(sess, last, last + 1.0) == []               # ros_lib waits 1 s
    last = _stream(sess, last + 1.0, 0.011, 3)                # then publishes again
    assert sess.device_waits(last) == []
    assert len(_ticks(sess, last + 0.45, last + 0.6)) == 1


def test_a_parameter_wait_lasts_as_long_as_rosserial_python_s_lastsync():
    sess = session.HostSession(sync_timeout=0.5)
    last = _streaming_with_services(sess)
    sess.on_frame(Frame(protocol.ID_PARAMETER_REQUEST, struct.pack('<I', 2) + b'~x'), last, 0)
    assert _ticks(sess, last, last + session.LOST_AFTER_MAX_S) == []
    assert len(_ticks(sess, last + session.LOST_AFTER_MAX_S, last + 15.1)) == 1


def test_an_answered_parameter_ends_the_wait_at_once():
    sess = session.HostSession(sync_timeout=0.5)
    last = _streaming_with_services(sess)
    sess.on_frame(Frame(protocol.ID_PARAMETER_REQUEST, struct.pack('<I', 2) + b'~x'), last, 0)
    sess.sent(protocol.ID_PARAMETER_REQUEST, last + 0.01)
    assert sess.device_waits(last + 0.01) == []
    assert len(_ticks(sess, last + 0.45, last + 0.6)) == 1


def test_a_request_to_the_device_s_server_holds_the_link_until_its_response():
    sess = session.HostSession(sync_timeout=0.5)
    last = _streaming_with_services(sess)
    sess.sent(121, last)                                      # the laptop's call, forwarded
    assert sess.device_waits(last) == [('server', '/srv1')]
    assert _ticks(sess, last, last + 3.0) == []
    sess.on_frame(Frame(120, b'response'), last + 3.0, 0)
    assert sess.device_waits(last + 3.0) == []
    assert len(_ticks(sess, last + 3.45, last + 3.6)) == 1


def test_every_lost_sync_carries_its_running_count():
    sess = session.HostSession(sync_timeout=0.5)
    counts, t = [], 0.0
    for _ in range(5):
        _handshake(sess, t)
        t = _stream(sess, t, 0.011, 10)
        counts += [e.data[0] for e in _ticks(sess, t, t + 8.0)]
        t += 8.0
    assert counts == [1, 2, 3, 4, 5] and sess.lost_syncs == 5


def test_session_takes_service_topic_info_while_up():
    # a ServiceServer's TopicInfo is no device reset
    sess = session.HostSession()
    _handshake(sess)
    for kind, topic_id in ((2, 120), (3, 121), (4, 122), (5, 123)):
        info = messages.TopicInfo(topic_id, '/srv', 'std_srvs/Trigger', 'md5', 300)
        data, events = sess.on_frame(Frame(kind, messages.encode_topic_info(info)), 0.1, 0)
        assert data == b'' and events[0].kind == 'service'
    assert sess.state == session.UP and sess.lost_syncs == 0
    assert sess.on_frame(Frame(120, b'r'), 0.2, 0)[1] == [('service_frame', (120, b'r'))]
    assert sess.services[121][:2] == ('server', 'request')
    assert sess.services[122][:2] == ('client', 'request')
    assert sess.buffer_size(121) == 300
    assert sess.max_publish_size() == 512


def test_session_takes_topic_info_again_and_larger_buffers():
    # a reset device announces itself while we are up: no renegotiation
    sess = session.HostSession()
    _handshake(sess)
    info = messages.TopicInfo(100, '/pirate/Small_State', 'pirate/SmallState', 'md5', 1024)
    data, events = sess.on_frame(Frame(0, messages.encode_topic_info(info)), 0.1, 0)
    assert data == b'' and events == [('publisher', info)] and sess.state == session.UP
    assert sess.max_publish_size() == 1024


def test_session_unknown_topic_means_device_reset():
    sess = session.HostSession()
    _handshake(sess)
    assert sess.on_frame(Frame(100, b'x'), 0.1, 0)[1] == [('message', (100, b'x'))]
    data, events = sess.on_frame(Frame(150, b''), 0.2, 0)
    assert data == TOPIC_REQUEST and sess.state == session.NEGOTIATING


def test_session_rejects_bad_topic_info():
    sess = session.HostSession()
    sess.opened(0.0)
    _, events = sess.on_frame(Frame(protocol.ID_PUBLISHER, b'\x01\x02'), 0.0, 0)
    assert events[0].kind == 'error'
    _, events = sess.on_frame(_info_frame(protocol.ID_PUBLISHER, 7, '/x'), 0.0, 0)
    assert events[0].kind == 'error' and not sess.publishers


def test_session_asks_owner_for_param_and_encodes_as_ros_lib_expects():
    sess = session.HostSession()
    sess.opened(0.0)
    request = struct.pack('<I', 5) + b'~gain'
    data, events = sess.on_frame(Frame(protocol.ID_PARAMETER_REQUEST, request), 0.0, 0)
    assert data == b'' and events == [('param', '~gain')]
    reply = FrameParser().feed(sess.param_reply([1, 2]))[0]
    assert reply.topic == protocol.ID_PARAMETER_REQUEST
    assert reply.payload == struct.pack('<IiiII', 2, 1, 2, 0, 0)
    assert messages.encode_param_value(True) == struct.pack('<IiII', 1, 1, 0, 0)
    assert messages.encode_param_value(0.5) == struct.pack('<IIfI', 0, 1, 0.5, 0)
    assert messages.encode_param_value('ab') == struct.pack('<IIII', 0, 0, 1, 2) + b'ab'
    for bad in ({'a': 1}, [1, 'a'], [], None):
        with pytest.raises(ValueError):
            messages.encode_param_value(bad)


def test_other_protocol_version_is_counted_with_its_byte():
    hydro_minus = bytes([0xFF, 0xFD]) + TOPIC_REQUEST[2:]
    parser = FrameParser()
    assert parser.feed(hydro_minus + TX_STOP) == [Frame(11, b'')]
    assert parser.stats.version_errors == 1 and parser.last_version == 0xFD
    garbage = FrameParser()
    garbage.feed(bytes([0xFF, 0x12, 0x34, 0x56, 0x00]))   # no valid length checksum
    assert garbage.stats.version_errors == 0


# -- outbox ------------------------------------------------------------------
def test_outbox_keeps_latest_only_and_drops_stale():
    box = Outbox(max_age=0.2)
    for i in range(50):
        box.put('/sp', bytes([i]), now=i * 0.01)
    box.put('/ctl', b'c', now=0.0)
    assert box.take(now=0.55) == [('/sp', bytes([49]))]
    assert box.stale_dropped == 1 and box.replaced == 49
    assert box.take(now=1.0) == []
