"""MIDI driver logic without hardware: device choice, decoding, unplug/replug."""
import pytest

from pirate.panel import midi
from pirate.panel.midi import DeviceInfo

THROUGH_IN = DeviceInfo(0, 'ALSA', 'Midi Through Port-0', True, False)
THROUGH_OUT = DeviceInfo(1, 'ALSA', 'Midi Through Port-0', False, True)
KORG_IN = DeviceInfo(2, 'ALSA', 'nanoKONTROL2 MIDI 1', True, False)
KORG_OUT = DeviceInfo(3, 'ALSA', 'nanoKONTROL2 MIDI 1', False, True)
ALL = [THROUGH_IN, THROUGH_OUT, KORG_IN, KORG_OUT]


@pytest.mark.parametrize('wanted,want_input,expected', [
    ('', True, KORG_IN), ('', False, KORG_OUT), ('nanokontrol', True, KORG_IN),
    ('3', False, KORG_OUT), ('2', False, None), ('launchpad', True, None), ('0', True, THROUGH_IN)])
def test_select(wanted, want_input, expected):
    assert midi.select(ALL, wanted, want_input) == expected


def test_decode_keeps_control_changes_only():
    raw = [(0xB0, 42, 127), (0xF8, 0, 0), (0x90, 60, 100), (0xBF, 4, 12)]
    assert midi.decode(raw) == [(42, 127), (4, 12)]


def test_encode_led():
    assert midi.encode_led(43, True) == (0xB0, 43, 127)
    assert midi.encode_led(43, False) == (0xB0, 43, 0)


class Port(object):
    def __init__(self):
        self.queue, self.written, self.broken = [], [], False

    def read(self):
        if self.broken:
            raise IOError('device unplugged')
        out, self.queue = self.queue, []
        return out

    def write(self, *msg):
        if self.broken:
            raise IOError('device unplugged')
        self.written.append(msg)


class Backend(object):
    def __init__(self, devices):
        self.list, self.ports, self.closed = list(devices), [], 0

    def rescan(self):
        pass

    def devices(self):
        return list(self.list)

    def open(self, info):
        self.ports.append(Port())
        return self.ports[-1]

    def close(self, port):
        self.closed += 1

    def present(self, info):
        return info in self.list


def test_waits_with_one_message_then_opens_when_plugged():
    backend, logs = Backend([THROUGH_IN]), []
    link = midi.MidiLink(backend, 'nanoKONTROL2', True, logs.append, retry_s=1.0)
    for t in range(5):
        assert not link.step(float(t))
    assert len(logs) == 1 and 'no MIDI input device' in logs[0] and 'waiting' in logs[0]
    backend.list.append(KORG_IN)
    assert link.step(5.0) and 'opened' in logs[-1]


def test_unplug_during_read_then_replug():
    backend, logs = Backend([KORG_IN]), []
    link = midi.MidiLink(backend, '', True, logs.append)
    link.step(0.0)
    backend.ports[0].queue = [(0xB0, 1, 64)]
    assert link.read() == [(1, 64)]
    backend.ports[0].broken = True
    assert link.read() == []
    assert not link.connected and 'lost' in logs[-1] and backend.closed == 1
    link.step(0.5)                     # retries at once after a loss
    assert link.connected and len(backend.ports) == 2


def test_unplug_noticed_by_presence_check():
    backend, logs = Backend([KORG_OUT]), []
    link = midi.MidiLink(backend, '', False, logs.append, check_s=1.0)
    link.step(0.0)
    assert link.write_led(43, True) and backend.ports[0].written == [(0xB0, 43, 127)]
    backend.list = []
    link.step(1.0)
    assert not link.connected and 'no longer listed' in logs[-1]
    assert not link.write_led(43, False)
    link.step(2.0)
    link.step(3.0)
    assert len([line for line in logs if 'waiting for one' in line]) == 1
