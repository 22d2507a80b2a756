"""MIDI device choice, message coding and reconnection (report 5.4).

Pure logic for the MIDI driver nodes; the pygame.midi calls sit behind a
small backend object (pirate.panel.midi_backend) so that choosing a device,
decoding control changes and surviving an unplug are unit-tested without
hardware.

A backend provides ``rescan()``, ``devices() -> [DeviceInfo]``,
``open(info) -> port``, ``present(info) -> bool``, ``close(port)``; a port
provides ``read() -> [(status, data1, data2)]`` (input) or
``write(status, data1, data2)`` (output). Any exception from a port or
``present() == False`` means the device has gone.
"""
import collections

DeviceInfo = collections.namedtuple('DeviceInfo', 'id interface name is_input is_output')

CONTROL_CHANGE = 0xB0
LED_ON, LED_OFF = 127, 0
#: ALSA's loop-back port is always there and never a panel.
_NOT_A_PANEL = ('midi through',)


def describe(devices):
    """One line per device, for ``midi_devices`` and log messages."""
    if not devices:
        return 'no MIDI devices present'
    return '\n'.join('%3d  %-6s %s%s' % (d.id, d.interface, d.name,
                                         (' [in]' if d.is_input else '') + (' [out]' if d.is_output else ''))
                     for d in devices)


def select(devices, wanted, want_input):
    """The device to open: by id (``wanted`` all digits), by name part, or
    the first non-loop-back device of the right direction (``wanted`` '')."""
    usable = [d for d in devices if (d.is_input if want_input else d.is_output)]
    wanted = str(wanted).strip()
    if wanted.isdigit():
        return next((d for d in usable if d.id == int(wanted)), None)
    if wanted:
        return next((d for d in usable if wanted.lower() in d.name.lower()), None)
    return next((d for d in usable if not d.name.lower().startswith(_NOT_A_PANEL)), None)


def decode(messages):
    """(channel, value) of every control change in raw (status, d1, d2) messages.

    On a nanoKONTROL2 in CC mode every control is a control change; the MIDI
    channel nibble is ignored (the panel's global channel). Other messages
    (clock, sysex) are skipped.
    """
    return [(data1, data2) for status, data1, data2 in messages
            if status & 0xF0 == CONTROL_CHANGE]


def encode_led(button, on):
    """The control change that lights (or clears) the LED of ``button``.

    The nanoKONTROL2 must be in "external" LED mode (Korg Kontrol Editor) for
    the laptop to own its LEDs.
    """
    return CONTROL_CHANGE, int(button) & 0x7F, LED_ON if on else LED_OFF


class MidiLink(object):
    """Keep one MIDI port open, reopening it after an unplug.

    ``wanted``: id or name part ('' = first panel); ``want_input``: input or
    output side; ``log(text)``: operator messages (each situation once);
    ``retry_s``: how often to look for the device while it is missing;
    ``check_s``: how often to check that an open device is still there.
    """

    def __init__(self, backend, wanted, want_input, log, retry_s=1.0, check_s=1.0):
        self._backend = backend
        self._wanted = wanted
        self._want_input = want_input
        self._log = log
        self._retry_s, self._check_s = retry_s, check_s
        self.port = None
        self.info = None
        self._next_scan = 0.0
        self._next_check = 0.0
        self._last_absent = None

    @property
    def connected(self):
        return self.port is not None

    def step(self, now):
        """Open the device if it is due and missing; drop it if it vanished."""
        if self.port is None:
            if now >= self._next_scan:
                self._next_scan = now + self._retry_s
                self._try_open()
        elif now >= self._next_check:
            self._next_check = now + self._check_s
            try:
                present = self._backend.present(self.info)
            except Exception as err:  # noqa: BLE001 - any backend failure means gone
                present, reason = False, str(err)
            else:
                reason = 'it is no longer listed'
            if not present:
                self.lost(reason)
        return self.connected

    def _try_open(self):
        try:
            self._backend.rescan()
            devices = self._backend.devices()
        except Exception as err:  # noqa: BLE001
            self._absent('cannot list MIDI devices (%s)' % err)
            return
        info = select(devices, self._wanted, self._want_input)
        if info is None:
            side = 'input' if self._want_input else 'output'
            self._absent('no MIDI %s device matching %r; present:\n%s\nwaiting for one '
                         '(plug the panel in, or set ~device to an id or name from '
                         'midi_devices)' % (side, self._wanted or 'any panel', describe(devices)))
            return
        try:
            self.port = self._backend.open(info)
        except Exception as err:  # noqa: BLE001
            self._absent('cannot open MIDI device %d %r (%s); retrying' % (info.id, info.name, err))
            return
        self.info = info
        self._last_absent = None
        self._log('MIDI device %d %r opened' % (info.id, info.name))

    def _absent(self, text):
        if text != self._last_absent:
            self._last_absent = text
            self._log(text)

    def lost(self, reason):
        """The device has gone (unplug, I/O error): close and look again."""
        if self.port is None:
            return
        name = self.info.name
        try:
            self._backend.close(self.port)
        except Exception:  # noqa: BLE001 - closing a vanished device may fail too
            pass
        self.port, self.info = None, None
        self._next_scan = 0.0
        self._log('MIDI device %r lost (%s); waiting for it to come back' % (name, reason))

    def read(self):
        """Control changes received since the last call; [] when disconnected."""
        if self.port is None:
            return []
        try:
            return decode(self.port.read())
        except Exception as err:  # noqa: BLE001
            self.lost('read failed: %s' % err)
            return []

    def write_led(self, button, on):
        """Send one LED change; False when it could not be sent."""
        if self.port is None:
            return False
        try:
            self.port.write(*encode_led(button, on))
            return True
        except Exception as err:  # noqa: BLE001
            self.lost('write failed: %s' % err)
            return False
