"""rosserial frames: encoding, checksums and an incremental parser.

Wire format (wiki.ros.org/rosserial/Overview/Protocol, Noetic)::

    0xFF  0xFE  len_lo len_hi  len_chk  topic_lo topic_hi  payload...  msg_chk

- ``len`` is the payload length in bytes (little-endian uint16);
- ``len_chk  = 255 - ((len_lo + len_hi) % 256)``;
- ``msg_chk  = 255 - ((topic_lo + topic_hi + sum(payload)) % 256)``.

The parser never trusts a byte until both checksums match: on any mismatch it
drops only the 0xFF it had taken for a sync byte and scans on from the next
byte, so a valid frame hidden after garbage (or inside a truncated frame) is
still found. Pure: no port, no ROS, no clock.
"""
import collections
import struct

SYNC = 0xFF
PROTOCOL_VERSION = 0xFE          # Hydro and later, incl. Noetic
HEADER_SIZE = 7                  # sync, version, len lo/hi, len chk, topic lo/hi
OVERHEAD = HEADER_SIZE + 1       # plus the message checksum

# Topic ids with a fixed meaning (rosserial_msgs/TopicInfo); device topics
# are numbered from FIRST_USER_TOPIC.
ID_PUBLISHER = 0
ID_SUBSCRIBER = 1
ID_SERVICE_SERVER = 2
ID_SERVICE_CLIENT = 4
ID_PARAMETER_REQUEST = 6
ID_LOG = 7
ID_TIME = 10
ID_TX_STOP = 11
FIRST_USER_TOPIC = 100

#: Largest payload the parser accepts until the device announces a larger
#: buffer (TopicInfo.buffer_size; the host raises ``max_payload`` to it).
#: rosserial_arduino's default buffers are 512 bytes on a Mega.
DEFAULT_MAX_PAYLOAD = 512

Frame = collections.namedtuple('Frame', 'topic payload')


def length_checksum(length):
    """Checksum byte of a uint16 payload length."""
    return 255 - (((length & 0xFF) + (length >> 8)) % 256)


def message_checksum(topic, payload):
    """Checksum byte over the topic id and the payload."""
    return 255 - (((topic & 0xFF) + (topic >> 8) + sum(payload)) % 256)


def encode(topic, payload=b''):
    """Return the bytes of one frame carrying ``payload`` on ``topic``."""
    payload = bytes(payload)
    if not 0 <= topic <= 0xFFFF:
        raise ValueError('topic id %r outside 0..65535' % (topic,))
    if len(payload) > 0xFFFF:
        raise ValueError('payload of %d bytes exceeds 65535' % len(payload))
    length = len(payload)
    return (struct.pack('<BBHBH', SYNC, PROTOCOL_VERSION, length,
                        length_checksum(length), topic)
            + payload + bytes((message_checksum(topic, payload),)))


class Stats(object):
    """Counters of what the parser saw; read by the host's diagnostics."""

    __slots__ = ('frames', 'bytes', 'skipped', 'length_errors',
                 'checksum_errors', 'version_errors', 'oversize')

    def __init__(self):
        for name in self.__slots__:
            setattr(self, name, 0)


class FrameParser(object):
    """Incremental parser: feed bytes in any chunking, get whole frames back.

    ``feed(data)`` returns the list of :class:`Frame` completed by ``data``.
    Every frame returned passed both checksums. ``resyncs`` counts the times
    the parser had to throw bytes away to find the next frame. A sync byte
    followed by another version byte and a valid length checksum is a frame
    of another rosserial release: counted in ``stats.version_errors``, its
    version byte kept in ``last_version`` (the host reports it).
    """

    def __init__(self, max_payload=DEFAULT_MAX_PAYLOAD):
        self.max_payload = max_payload
        self.stats = Stats()
        self.resyncs = 0
        self.last_version = None
        self._buf = bytearray()
        self._dropping = False

    def reset(self):
        """Forget buffered bytes (after the port was reopened)."""
        del self._buf[:]
        self._dropping = False

    def pending(self):
        """Number of buffered bytes not yet part of a delivered frame."""
        return len(self._buf)

    def _drop(self, count):
        """Discard ``count`` bytes that are not a frame; count one resync per run."""
        del self._buf[:count]
        self.stats.skipped += count
        if not self._dropping:
            self._dropping = True
            self.resyncs += 1

    def feed(self, data):
        """Consume ``data``; return the frames it completed, in order."""
        buf = self._buf
        buf.extend(data)
        self.stats.bytes += len(data)
        frames = []
        while buf:
            start = buf.find(SYNC)
            if start < 0:
                self._drop(len(buf))
                break
            if start:
                self._drop(start)
            if len(buf) < 2:
                break
            if buf[1] != PROTOCOL_VERSION:
                if buf[1] != SYNC:
                    if len(buf) < 5:
                        break   # a frame of another protocol version? wait for its length
                    if buf[4] == length_checksum(buf[2] | (buf[3] << 8)):
                        self.stats.version_errors += 1
                        self.last_version = buf[1]
                self._drop(1)
                continue
            if len(buf) < 5:
                break
            length = buf[2] | (buf[3] << 8)
            if buf[4] != length_checksum(length):
                self.stats.length_errors += 1
                self._drop(1)
                continue
            if length > self.max_payload:
                self.stats.oversize += 1
                self._drop(1)
                continue
            end = OVERHEAD + length
            if len(buf) < end:
                break
            topic = buf[5] | (buf[6] << 8)
            payload = bytes(buf[HEADER_SIZE:end - 1])
            if buf[end - 1] != message_checksum(topic, payload):
                self.stats.checksum_errors += 1
                self._drop(1)
                continue
            del buf[:end]
            self._dropping = False
            self.stats.frames += 1
            frames.append(Frame(topic, payload))
        return frames
