"""The Mega <-> PICO RS485 bus: frame codec, board map, and simulated boards.

The report gives no bus protocol; ours is defined in firmware/README.md and
mirrored here byte for byte (the firmware's C++ and this module are checked
against each other by test/unit/test_firmware_*.py). Summary::

    0xA5  addr  type  seq  len  payload[len]  crc8(addr..payload)

- master -> board: SET (0x01, 8 bytes: mode0 u8, mode1 u8, setpoint0 i16,
  setpoint1 i16, torque limit u16) or STOP (0x02, 0 bytes; addr 0xFF =
  every board, no reply);
- board -> master: STATE (0x81, 18 bytes: the nine int16 of Table B.1),
  within REPLY_TIMEOUT_MS of a request addressed to it.

:class:`SimPicoBoards` plays the nine boards for firmware-in-the-loop: it
decodes what the (native) firmware sends, latches each board's command,
turns the latched commands back into the laptop's three arrays for
:class:`pirate.sim.twin.TwinRobot`, and answers with the model's state.
Pure: no ROS, no I/O; bytes and times in, bytes and records out.
"""
import collections
import struct

from pirate.robot import safety, tables

START = 0xA5
BROADCAST = 0xFF
SET, STOP, STATE = 0x01, 0x02, 0x81
PAYLOAD_SIZE = {SET: 8, STOP: 0, STATE: 2 * tables.SMALL_STATE_SIZE}
HEADER = 5
BUS_BAUD = 115200
REPLY_TIMEOUT_MS = 5
NO_ELEMENT = -1

#: What the Mega sends each board: (board, setpoint0 index, setpoint1 index,
#: mode0 index, mode1 index, limit index, wheel sign of motor 1), indices
#: into the laptop's arrays, NO_ELEMENT where the motor has none.
BoardMap = collections.namedtuple('BoardMap', 'board sp0 sp1 mode0 mode1 limit sign1')


def _board_map():
    rows = []
    for board in tables.BOARDS:
        sp0 = tables.index_of(board, 0)
        sp1 = tables.index_of(board, 1)
        mode1 = sp1 if sp1 < tables.CONTROL_SIZE else NO_ELEMENT
        name = tables.SETPOINT_ELEMENTS[sp0].name
        limit = (tables.LIMIT_ELEMENTS.index(name) if name in tables.LIMIT_ELEMENTS
                 else NO_ELEMENT)
        rows.append(BoardMap(board, sp0, sp1, sp0, mode1, limit, tables.WHEEL_SIGN.get(board, 1)))
    return tuple(rows)


BOARD_MAP = _board_map()
_MAP_BY_BOARD = {row.board: row for row in BOARD_MAP}


def crc8(data):
    """CRC-8, polynomial 0x07, initial value 0 (CRC-8/SMBUS)."""
    crc = 0
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = ((crc << 1) ^ 0x07) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
    return crc


def encode(addr, kind, seq, payload=b''):
    """One bus frame."""
    body = bytes((addr, kind, seq & 0xFF, len(payload))) + bytes(payload)
    return bytes((START,)) + body + bytes((crc8(body),))


def encode_set(addr, seq, mode0, mode1, setpoint0, setpoint1, limit):
    return encode(addr, SET, seq, struct.pack('<BBhhH', mode0 & 0xFF, mode1 & 0xFF,
                                              setpoint0, setpoint1, limit))


def encode_state(addr, seq, data):
    return encode(addr, STATE, seq, struct.pack('<9h', *data))


BusFrame = collections.namedtuple('BusFrame', 'addr kind seq payload')


class BusParser(object):
    """Incremental bus frame parser; drops a start byte and rescans on any error."""

    def __init__(self):
        self._buf = bytearray()
        self.errors = 0

    def feed(self, data):
        buf = self._buf
        buf.extend(data)
        frames = []
        while buf:
            start = buf.find(START)
            if start < 0:
                del buf[:]
                break
            del buf[:start]
            if len(buf) < HEADER:
                break
            kind, length = buf[2], buf[4]
            if PAYLOAD_SIZE.get(kind) != length:
                self.errors += 1
                del buf[:1]
                continue
            end = HEADER + length + 1
            if len(buf) < end:
                break
            if crc8(buf[1:end - 1]) != buf[end - 1]:
                self.errors += 1
                del buf[:1]
                continue
            frames.append(BusFrame(buf[1], kind, buf[3], bytes(buf[HEADER:end - 1])))
            del buf[:end]
        return frames


BoardCommand = collections.namedtuple('BoardCommand', 'mode0 mode1 setpoint0 setpoint1 limit')


class SimPicoBoards(object):
    """Nine simulated PICO boards on one bus, around a simulated robot (the physics twin).

    ``log`` records every command a board applied as (time s, board,
    'set'/'stop', BoardCommand or None): the tests measure on it.
    """

    def __init__(self, model, keep_log=True):
        self.model = model
        self.parser = BusParser()
        self.commands = {board: None for board in tables.BOARDS}   # None = stopped
        self.log = [] if keep_log else None
        self.requests = 0

    def _record(self, now, board, what, command):
        if self.log is not None:
            self.log.append((now, board, what, command))

    def feed(self, data, now):
        """Bytes from the master; return the bytes the boards answer."""
        out = b''
        for frame in self.parser.feed(data):
            if frame.kind == STOP and frame.addr == BROADCAST:
                for board in tables.BOARDS:
                    self.commands[board] = None
                    self._record(now, board, 'stop', None)
                self._apply()
                continue
            if frame.addr not in self.commands or frame.kind not in (SET, STOP):
                continue
            self.requests += 1
            if frame.kind == SET:
                command = BoardCommand(*struct.unpack('<BBhhH', frame.payload))
                self.commands[frame.addr] = command
                self._record(now, frame.addr, 'set', command)
            else:
                self.commands[frame.addr] = None
                self._record(now, frame.addr, 'stop', None)
            self._apply()
            out += encode_state(frame.addr, frame.seq, self.model.small_state(frame.addr))
        return out

    def arrays(self):
        """The laptop's (setpoints13, modes12, limits4) the boards now hold.

        A stopped board's motors read PWM 0. The wheel element is taken
        from board 22 with its sign undone, 0 if any drive board is stopped.
        """
        setpoints = [0] * tables.SETPOINT_SIZE
        modes = [safety.MODE_CODES['pwm']] * tables.CONTROL_SIZE
        limits = [safety.NO_LIMIT] * tables.LIMIT_SIZE
        wheel_stopped = False
        for row in BOARD_MAP:
            command = self.commands[row.board]
            if command is None:
                wheel_stopped = wheel_stopped or row.board in tables.DRIVE_BOARDS
                continue
            setpoints[row.sp0] = command.setpoint0
            modes[row.mode0] = _signed8(command.mode0)
            if row.limit != NO_ELEMENT:
                limits[row.limit] = command.limit
            if row.board in tables.DRIVE_BOARDS:
                if row.board == tables.DRIVE_BOARDS[0]:
                    setpoints[row.sp1] = command.setpoint1 * row.sign1
                    modes[row.mode1] = _signed8(command.mode1)
            else:
                setpoints[row.sp1] = command.setpoint1
                if row.mode1 != NO_ELEMENT:
                    modes[row.mode1] = _signed8(command.mode1)
        if wheel_stopped:
            setpoints[tables.element('wheels').index] = 0
        return setpoints, modes, limits

    def _apply(self):
        self.model.command(*self.arrays())

    def all_stopped_since(self, since):
        """Time (s) by which every board had been stopped after ``since``, or None."""
        latest = {}
        for now, board, what, _ in self.log:
            if now < since:
                continue
            if what == 'stop':
                latest.setdefault(board, now)
            else:
                latest.pop(board, None)
        if len(latest) < len(tables.BOARDS):
            return None
        return max(latest.values())


def _signed8(byte):
    return byte - 256 if byte > 127 else byte
