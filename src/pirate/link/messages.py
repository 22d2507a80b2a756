"""Payloads of rosserial's own topics, serialised as ROS 1 messages are.

rosserial_msgs/TopicInfo, std_msgs/Time, rosserial_msgs/Log and the
parameter request/response, written out with ``struct`` so the codec needs
no ROS installation (ROS 1 serialisation: little-endian, strings as uint32
length + bytes, arrays as uint32 count + elements). Pure.
"""
import collections
import struct

TopicInfo = collections.namedtuple(
    'TopicInfo', 'topic_id topic_name message_type md5sum buffer_size')

# rosserial_msgs/Log levels.
LOG_LEVELS = {0: 'debug', 1: 'info', 2: 'warn', 3: 'error', 4: 'fatal'}


class DecodeError(ValueError):
    """A payload that does not deserialise as the expected message."""


def _pack_string(text):
    data = text.encode('utf-8')
    return struct.pack('<I', len(data)) + data


class _Reader(object):
    """Cursor over a payload; every read is bounds-checked."""

    def __init__(self, data):
        self.data = bytes(data)
        self.pos = 0

    def take(self, count):
        if count < 0 or self.pos + count > len(self.data):
            raise DecodeError('payload too short: need %d bytes at offset %d of %d'
                              % (count, self.pos, len(self.data)))
        chunk = self.data[self.pos:self.pos + count]
        self.pos += count
        return chunk

    def unpack(self, fmt):
        return struct.unpack(fmt, self.take(struct.calcsize(fmt)))

    def string(self):
        (length,) = self.unpack('<I')
        try:
            return self.take(length).decode('utf-8')
        except UnicodeDecodeError as error:
            raise DecodeError('string is not UTF-8: %s' % error)

    def done(self):
        if self.pos != len(self.data):
            raise DecodeError('%d trailing bytes' % (len(self.data) - self.pos))


def encode_topic_info(info):
    """Serialise a :class:`TopicInfo`."""
    return (struct.pack('<H', info.topic_id) + _pack_string(info.topic_name)
            + _pack_string(info.message_type) + _pack_string(info.md5sum)
            + struct.pack('<i', info.buffer_size))


def decode_topic_info(payload):
    """Deserialise a TopicInfo payload; :class:`DecodeError` if malformed."""
    reader = _Reader(payload)
    (topic_id,) = reader.unpack('<H')
    name, msg_type, md5 = reader.string(), reader.string(), reader.string()
    (size,) = reader.unpack('<i')
    reader.done()
    return TopicInfo(topic_id, name, msg_type, md5, size)


def encode_time(secs, nsecs):
    """Serialise std_msgs/Time (uint32 secs, uint32 nsecs)."""
    return struct.pack('<II', secs & 0xFFFFFFFF, nsecs)


def time_from_seconds(seconds):
    """(secs, nsecs) of a float time in seconds."""
    secs = int(seconds)
    nsecs = int(round((seconds - secs) * 1e9))
    if nsecs >= 1000000000:
        secs, nsecs = secs + 1, nsecs - 1000000000
    return secs, nsecs


def decode_time(payload):
    """(secs, nsecs) of a std_msgs/Time payload."""
    reader = _Reader(payload)
    secs, nsecs = reader.unpack('<II')
    reader.done()
    return secs, nsecs


def decode_log(payload):
    """(level name, text) of a rosserial_msgs/Log payload."""
    reader = _Reader(payload)
    (level,) = reader.unpack('<B')
    text = reader.string()
    reader.done()
    return LOG_LEVELS.get(level, 'info'), text


def decode_param_request(payload):
    """Parameter name of a rosserial_msgs/RequestParam request."""
    reader = _Reader(payload)
    name = reader.string()
    reader.done()
    return name


def encode_param_response(ints=(), floats=(), strings=()):
    """Serialise rosserial_msgs/RequestParam's response (int32[], float32[], string[])."""
    out = struct.pack('<I', len(ints)) + b''.join(struct.pack('<i', v) for v in ints)
    out += struct.pack('<I', len(floats)) + b''.join(struct.pack('<f', v) for v in floats)
    out += struct.pack('<I', len(strings)) + b''.join(_pack_string(s) for s in strings)
    return out


def encode_param_value(value):
    """RequestParam response carrying ``value``, typed as ros_lib's getParam
    expects: ints (bools as 0/1), floats or strings, one value or a list of
    one type. ValueError, naming the reason, for anything else (a dict, a
    mixed or empty list, None): the host then sends no answer, as
    rosserial_python does, and the device's getParam times out."""
    values = list(value) if isinstance(value, (list, tuple)) else [value]
    if not values:
        raise ValueError('an empty list cannot be sent')
    kinds = {_param_kind(v) for v in values}
    if len(kinds) != 1:
        raise ValueError('all elements must have one type (ints, floats or strings)')
    kind = kinds.pop()
    if kind == 'ints':
        return encode_param_response(ints=[int(v) for v in values])
    if kind == 'floats':
        return encode_param_response(floats=values)
    return encode_param_response(strings=values)


def _param_kind(value):
    if isinstance(value, (bool, int)):
        return 'ints'
    if isinstance(value, float):
        return 'floats'
    if isinstance(value, str):
        return 'strings'
    raise ValueError('a %s cannot be sent (ints, floats or strings only)' % type(value).__name__)
