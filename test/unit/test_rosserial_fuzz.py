"""Property and fuzz tests of the rosserial stream parser.

Properties, over random, mutated and garbage-prefixed streams in random
chunkings:
1. no exception;
2. every delivered frame re-encodes to exactly the bytes it came from, i.e.
   both checksums were right (checked against an independent brute-force
   scanner, :func:`oracle`, which the incremental parser must match);
3. resync: garbage without a sync byte followed by valid frames delivers
   every one of them.
Counts: hypothesis examples plus a seeded plain loop; together more than
100 000 streams, bounded to a few seconds.
"""
import random
import struct

from hypothesis import given, settings, strategies as st, HealthCheck

from pirate.link import protocol
from pirate.link.protocol import Frame, FrameParser

MAX_PAYLOAD = 64
LOOP_STREAMS = 100000


def oracle(stream, max_payload=MAX_PAYLOAD):
    """Frames of ``stream`` by brute force: at each position, a frame if
    every field checks, else move one byte on. Written independently of the
    parser, straight from the protocol's definition.

    A good header whose body runs past the end of the stream is a frame
    still arriving: a parser fed byte by byte cannot yet tell whether it is
    one, so nothing after it can be delivered either; the scan stops there.
    """
    frames, pos, n = [], 0, len(stream)
    while pos + protocol.OVERHEAD <= n:
        if stream[pos] == 0xFF and stream[pos + 1] == 0xFE:
            length = stream[pos + 2] + 256 * stream[pos + 3]
            if (length <= max_payload
                    and (stream[pos + 2] + stream[pos + 3] + stream[pos + 4]) % 256 == 255):
                if pos + 8 + length > n:
                    break
                body = stream[pos + 5:pos + 8 + length]
                if sum(body) % 256 == 255:
                    topic = body[0] + 256 * body[1]
                    frames.append(Frame(topic, bytes(body[2:-1])))
                    pos += 8 + length
                    continue
        pos += 1
    return frames


def feed_chunked(stream, cuts, max_payload=MAX_PAYLOAD):
    parser = FrameParser(max_payload=max_payload)
    out, last = [], 0
    for cut in sorted(set(c % (len(stream) + 1) for c in cuts)) + [len(stream)]:
        out.extend(parser.feed(stream[last:cut]))
        last = cut
    return out, parser


def check_stream(stream, cuts):
    frames, _ = feed_chunked(stream, cuts)
    for frame in frames:
        assert protocol.encode(frame.topic, frame.payload) in stream
    assert frames == oracle(stream)
    return frames


frames_st = st.lists(st.tuples(st.integers(0, 0xFFFF), st.binary(max_size=MAX_PAYLOAD)),
                     min_size=1, max_size=4)


def mutate(data, rng, count):
    """Flip, insert, delete or duplicate bytes, the damage a noisy line does."""
    data = bytearray(data)
    for _ in range(count):
        pos = rng.randrange(len(data) + 1)
        op = rng.randrange(4)
        if op == 0 and pos < len(data):
            data[pos] ^= 1 << rng.randrange(8)
        elif op == 1:
            data[pos:pos] = bytes([rng.choice((0xFF, 0xFE, rng.randrange(256)))])
        elif op == 2 and pos < len(data):
            del data[pos]
        elif op == 3:
            data[pos:pos] = data[pos:pos + rng.randrange(1, 9)]
    return bytes(data)


@settings(max_examples=800, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.binary(max_size=200), st.lists(st.integers(0, 400), max_size=6))
def test_random_bytes_never_yield_a_bad_frame(stream, cuts):
    check_stream(stream, cuts)


def test_frame_still_arriving_hides_the_bytes_inside_it():
    """A good header announcing 6 bytes, then 13 bytes that hold a whole
    empty frame: until the 6 bytes are in and checked, the parser may not
    deliver what lies inside them (found by hypothesis)."""
    first = protocol.encode(6, b'')
    inside = protocol.encode(0, b'')
    stream = first + bytes([0xFF, 0xFE, 6, 0, 0xF9]) + inside
    assert oracle(stream) == [Frame(6, b'')]
    assert check_stream(stream, []) == [Frame(6, b'')]
    assert check_stream(stream + bytes(3), []) == [Frame(6, b''), Frame(0, b'')]


@settings(max_examples=800, deadline=None)
@given(frames_st, st.randoms(), st.integers(1, 6),
       st.lists(st.integers(0, 400), max_size=6))
def test_mutated_frames_match_oracle(frames, rng, count, cuts):
    stream = mutate(b''.join(protocol.encode(t, p) for t, p in frames), rng, count)
    check_stream(stream, cuts)


@settings(max_examples=800, deadline=None)
@given(st.lists(st.integers(0, 0xFE), max_size=120).map(bytes), frames_st,
       st.lists(st.integers(0, 400), max_size=6))
def test_resync_after_garbage_delivers_every_frame(garbage, frames, cuts):
    stream = garbage + b''.join(protocol.encode(t, p) for t, p in frames)
    delivered, parser = feed_chunked(stream, cuts)
    assert delivered == [Frame(t, p) for t, p in frames]
    assert parser.resyncs == (1 if garbage else 0)


@settings(max_examples=500, deadline=None)
@given(st.binary(min_size=1, max_size=60), frames_st)
def test_resync_after_any_garbage_then_idle_line(garbage, frames):
    """Any garbage, then a quiet gap the parser cannot mistake for data
    (a whole max-size frame's worth of 0x00 flushes a bogus header), then
    frames: all frames arrive."""
    flush = bytes(protocol.OVERHEAD + MAX_PAYLOAD)
    stream = garbage + flush + b''.join(protocol.encode(t, p) for t, p in frames)
    delivered, _ = feed_chunked(stream, [])
    assert delivered[-len(frames):] == [Frame(t, p) for t, p in frames]


def test_seeded_loop_of_random_and_mutated_streams():
    """The bulk count: LOOP_STREAMS short streams, half random bytes biased
    toward sync bytes, half mutated valid frames, each in random chunks."""
    rng = random.Random(20160705)
    delivered = 0
    for i in range(LOOP_STREAMS):
        if i % 2:
            size = rng.randrange(24)
            stream = bytes(rng.choice((0xFF, 0xFE, 0x00, rng.randrange(256)))
                           for _ in range(size))
        else:
            payload = bytes(rng.randrange(256) for _ in range(rng.randrange(6)))
            frame = protocol.encode(rng.randrange(0x10000), payload)
            stream = mutate(frame * rng.randrange(1, 3), rng, rng.randrange(3))
        cuts = [rng.randrange(len(stream) + 1)] if stream else []
        delivered += len(check_stream(stream, cuts))
    assert delivered > LOOP_STREAMS // 10   # the generator does produce frames


def test_frame_count_property_is_exact():
    """A deliberately long stream of back-to-back frames loses none."""
    rng = random.Random(7)
    frames = [(rng.randrange(100, 200), struct.pack('<13h', *[rng.randrange(-256, 257)
                                                              for _ in range(13)]))
              for _ in range(500)]
    stream = b''.join(protocol.encode(t, p) for t, p in frames)
    delivered, parser = feed_chunked(stream, [rng.randrange(len(stream)) for _ in range(100)])
    assert delivered == [Frame(t, p) for t, p in frames]
    assert parser.resyncs == 0 and parser.stats.checksum_errors == 0
