"""The PICO bus protocol (firmware/README.md) as pirate.sim.pico_bus
implements it, and the generated firmware header kept in step with the
Python sources of truth. No ROS master."""
import os
import random
import struct
import subprocess
import sys


from pirate.robot import tables
from pirate.msg import SetpointArray
from pirate.sim import pico_bus
from pirate.sim.pico_bus import BusFrame, BusParser, SimPicoBoards

FIRMWARE = os.path.join(os.path.dirname(__file__), '..', '..', 'firmware')


def test_crc8_check_value():
    # CRC-8/SMBUS (poly 0x07, init 0) check value over "123456789"
    assert pico_bus.crc8(b'123456789') == 0xF4


def test_set_frame_byte_layout():
    frame = pico_bus.encode_set(23, 7, 3, 1, -256, -50, 200)
    assert frame[:5] == bytes([0xA5, 23, 0x01, 7, 8])
    assert frame[5:13] == struct.pack('<BBhhH', 3, 1, -256, -50, 200)
    assert frame[13] == pico_bus.crc8(frame[1:13])
    assert len(frame) == 14


def test_parser_resyncs_and_rejects_bad_crc():
    good = pico_bus.encode_state(25, 3, list(range(9)))
    bad = bytearray(good)
    bad[7] ^= 1
    parser = BusParser()
    frames = parser.feed(b'\x00\xa5\x99' + bytes(bad) + good[:10])
    frames += parser.feed(good[10:])
    assert frames == [BusFrame(25, pico_bus.STATE, 3, struct.pack('<9h', *range(9)))]
    assert parser.errors >= 1


def test_board_map_follows_tables():
    rows = {row.board: row for row in pico_bus.BOARD_MAP}
    assert sorted(rows) == list(tables.BOARDS)
    for board in tables.DRIVE_BOARDS:
        assert rows[board].sp1 == tables.element('wheels').index
    assert rows[28].mode1 == pico_bus.NO_ELEMENT          # rear LED has no control mode
    assert [rows[b].limit for b in (22, 23, 26, 27)] == [0, 1, 2, 3]


class _Model(object):
    def __init__(self):
        self.commands = []

    def command(self, setpoints, modes, limits):
        self.commands.append((list(setpoints), list(modes), list(limits)))

    def small_state(self, board):
        return [board] * 9


def _frames_for(setpoints, modes, limits, seq=0):
    """What the firmware sends for the arrays (the firmware's mapping, in Python)."""
    out = b''
    for row in pico_bus.BOARD_MAP:
        mode1 = modes[row.mode1] if row.mode1 != pico_bus.NO_ELEMENT else 0
        limit = limits[row.limit] if row.limit != pico_bus.NO_ELEMENT else 0xFFFF
        out += pico_bus.encode_set(row.board, seq, modes[row.mode0], mode1,
                                   setpoints[row.sp0], setpoints[row.sp1] * row.sign1, limit)
    return out


def test_sim_boards_rebuild_the_laptop_arrays():
    rng = random.Random(3)
    for _ in range(50):
        setpoints = [rng.randrange(-256, 257) for _ in range(13)]
        modes = [rng.randrange(0, 11) for _ in range(12)]
        limits = [rng.randrange(0, 65536) for _ in range(4)]
        model = _Model()
        boards = SimPicoBoards(model)
        replies = boards.feed(_frames_for(setpoints, modes, limits), now=1.0)
        assert model.commands[-1] == (setpoints, modes, limits)
        got = BusParser().feed(replies)
        assert [f.addr for f in got] == list(tables.BOARDS)


def test_sim_boards_stop_broadcast_zeroes_everything():
    model = _Model()
    boards = SimPicoBoards(model)
    boards.feed(_frames_for([100] * 13, [1] * 12, [5] * 4), now=1.0)
    assert boards.feed(pico_bus.encode(pico_bus.BROADCAST, pico_bus.STOP, 0), now=2.0) == b''
    assert model.commands[-1][0] == [0] * 13
    assert boards.all_stopped_since(1.5) == 2.0
    assert boards.all_stopped_since(2.5) is None


def test_generated_header_is_current():
    result = subprocess.run([sys.executable, os.path.join(FIRMWARE, 'gen_header.py'), '--check'],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    assert result.returncode == 0, result.stdout.decode()


def test_generated_header_carries_our_md5():
    with open(os.path.join(FIRMWARE, 'PirateBay', 'pirate_generated.h')) as handle:
        text = handle.read()
    assert '#define TOPIC_SETPOINT_MD5 "%s"' % SetpointArray._md5sum in text
