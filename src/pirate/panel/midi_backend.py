"""pygame.midi behind the small backend interface of pirate.panel.midi.

The thin edge to PortMidi: PortMidi lists devices only at init, so
``rescan`` re-initialises it (only while no port is open), and an unplugged
device is noticed either by an I/O error or by its ALSA sequencer client
disappearing from /proc/asound/seq/clients (Linux).
"""
import os

os.environ.setdefault('PYGAME_HIDE_SUPPORT_PROMPT', '1')  # keep midi_devices output clean
import pygame.midi  # noqa: E402

from pirate.panel.midi import DeviceInfo  # noqa: E402

ALSA_CLIENTS = '/proc/asound/seq/clients'
READ_BATCH = 256


class _Input(object):
    def __init__(self, device_id):
        self._port = pygame.midi.Input(device_id)

    def read(self):
        messages = []
        while self._port.poll():
            messages.extend((data[0], data[1], data[2]) for data, _stamp in self._port.read(READ_BATCH))
        return messages

    def close(self):
        self._port.close()


class _Output(object):
    def __init__(self, device_id):
        self._port = pygame.midi.Output(device_id)

    def write(self, status, data1, data2):
        self._port.write_short(status, data1, data2)

    def close(self):
        self._port.close()


class PygameMidiBackend(object):
    """Devices and ports through pygame.midi (PortMidi)."""

    def __init__(self):
        self._open = 0

    def rescan(self):
        if self._open == 0:
            if pygame.midi.get_init():
                pygame.midi.quit()
            pygame.midi.init()

    def devices(self):
        if not pygame.midi.get_init():
            pygame.midi.init()
        found = []
        for device_id in range(pygame.midi.get_count()):
            interface, name, is_input, is_output, _opened = pygame.midi.get_device_info(device_id)
            found.append(DeviceInfo(device_id, interface.decode(errors='replace'),
                                    name.decode(errors='replace'), bool(is_input), bool(is_output)))
        return found

    def open(self, info):
        port = _Input(info.id) if info.is_input else _Output(info.id)
        self._open += 1
        return port

    def close(self, port):
        self._open = max(0, self._open - 1)
        port.close()

    def present(self, info):
        """False once the device's ALSA client is gone (True where unknowable)."""
        if not os.path.exists(ALSA_CLIENTS):
            return True
        with open(ALSA_CLIENTS) as stream:
            text = stream.read()
        # The file lists every client and port name; PortMidi's device name
        # is the ALSA port name (or "client:port" with some ALSA versions).
        return info.name in text or info.name.split(':')[0].strip() in text
