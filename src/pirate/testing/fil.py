"""Firmware in the loop: the native Pirate Bay firmware between a
pseudo-terminal (the laptop's "USB port") and simulated PICO boards.

::

    serial_node <-> pty slave (symlink ``link_path``) | pty master <-> relay
        <-> firmware stdin/stdout ... firmware bus socket <-> SimPicoBoards(twin)

The relay (one thread) is the cable: it paces bytes at the baud rate (10
bits per byte on the wire, 8N1), and can be *stalled* (nothing passes for a
while; the device's bytes are lost as a USB-serial chip would lose them)
or *unplugged* (the pty closes; plugging back opens a new one at the same
path and resets the firmware, as opening the Mega's port does through DTR);
the firmware can also be *reset* with the cable in, and one board *muted*
on the bus.
It also steps the model at the PICO loop rate (50 Hz). Time is wall time:
the firmware keeps its own millisecond clock, so FIL runs at rate 1.

No ROS: nodes/fil_robot wraps it for launch files, and the FIL rostests
drive it directly to measure on the simulated bus.
"""
import collections
import os
import select
import socket
import subprocess
import termios
import threading
import time
import tty

from pirate.link.protocol import FrameParser
from pirate.sim import pico_bus

PICO_PERIOD_S = 0.02
BITS_PER_BYTE = 10   # 8N1: start + 8 data + stop


class _Pacer(object):
    """Releases bytes no faster than a serial line of ``baud`` would."""

    def __init__(self, baud):
        self.byte_s = BITS_PER_BYTE / float(baud)
        self._queue = collections.deque()
        self._free_at = 0.0

    def push(self, data, now):
        done = max(now, self._free_at) + len(data) * self.byte_s
        self._free_at = done
        self._queue.append((done, data))

    def pop_ready(self, now):
        out = b''
        while self._queue and self._queue[0][0] <= now:
            out += self._queue.popleft()[1]
        return out

    def clear(self):
        self._queue.clear()


class FirmwareInTheLoop(object):
    """Run ``firmware`` (path of pirate_bay_native) against ``model``."""

    def __init__(self, firmware, model, link_path, baud=57600, clock=time.monotonic,
                 record=True):
        self.firmware = firmware
        self.model = model
        self.link_path = link_path
        self.baud = baud
        self.clock = clock
        self.record = record           # keep the logs below (tests; not in long runs)
        self.boards = pico_bus.SimPicoBoards(model, keep_log=record)
        self.host_frames = []          # (time s, topic id, payload) reaching the firmware
        self._host_parser = FrameParser()
        self.resets = 0
        self.muted = None              # a board that does not answer on the bus
        self._lock = threading.RLock()
        self._to_fw = _Pacer(baud)
        self._to_host = _Pacer(baud)
        self._master = None
        self._proc = None
        self._bus = None
        self._stalled_until = 0.0
        self._master_quiet_until = 0.0
        self._stop = threading.Event()
        self._thread = None
        self._last_step = None

    # -- lifecycle ------------------------------------------------------------
    def start(self):
        self._plug()
        self._start_firmware()
        self._last_step = self.clock()
        self._thread = threading.Thread(target=self._run, name='fil-relay')
        self._thread.daemon = True
        self._thread.start()

    def stop(self):
        self._stop.set()
        if self._thread:
            self._thread.join(2.0)
        self._stop_firmware()
        self._unplug()

    def _start_firmware(self):
        ours, theirs = socket.socketpair()
        self._proc = subprocess.Popen([self.firmware, str(theirs.fileno())],
                                      stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                      pass_fds=(theirs.fileno(),), bufsize=0)
        theirs.close()
        ours.setblocking(False)
        self._bus = ours
        os.set_blocking(self._proc.stdout.fileno(), False)

    def _stop_firmware(self):
        proc, self._proc = self._proc, None
        if proc is not None:
            proc.kill()
            proc.wait()
            proc.stdin.close()
            proc.stdout.close()
        if self._bus is not None:
            self._bus.close()
            self._bus = None

    def _plug(self):
        master, slave = os.openpty()
        tty.setraw(slave)
        attrs = termios.tcgetattr(slave)
        attrs[3] &= ~termios.ECHO
        termios.tcsetattr(slave, termios.TCSANOW, attrs)
        name = os.ttyname(slave)
        os.close(slave)   # the host opens it by name; master reads EIO until then
        os.set_blocking(master, False)
        tmp = self.link_path + '.new'
        if os.path.lexists(tmp):
            os.unlink(tmp)
        os.symlink(name, tmp)
        os.rename(tmp, self.link_path)
        self._master = master

    def _unplug(self):
        master, self._master = self._master, None
        if master is not None:
            os.close(master)
        if os.path.lexists(self.link_path):
            os.unlink(self.link_path)
        self._to_fw.clear()
        self._to_host.clear()

    # -- faults the tests inject ------------------------------------------------
    def unplug(self):
        """Pull the cable: the pty disappears; the firmware keeps running."""
        with self._lock:
            self._unplug()

    def replug(self):
        """Plug back in: a new pty at the same path, and the Mega resets."""
        with self._lock:
            self._stop_firmware()
            self._start_firmware()
            self.resets += 1
            self._host_parser.reset()
            self._plug()

    def reset(self):
        """The Mega resets with the cable in (watchdog, brown-out): same port,
        the firmware starts again from power-up; bytes on their way to it
        are lost."""
        with self._lock:
            self._stop_firmware()
            self._to_fw.clear()
            self._to_host.clear()
            self._start_firmware()
            self.resets += 1
            self._host_parser.reset()

    def mute(self, board=None):
        """Board ``board`` stops answering on the bus (None: all answer again)."""
        with self._lock:
            self.muted = board

    def stall(self, seconds):
        """Nothing crosses the link for ``seconds`` (device bytes are lost)."""
        with self._lock:
            self._stalled_until = self.clock() + seconds

    # -- relay ----------------------------------------------------------------
    def _run(self):
        while not self._stop.is_set():
            with self._lock:
                master = self._master if self.clock() >= self._master_quiet_until else None
                fds = [f for f in (master, self._proc and self._proc.stdout.fileno(),
                                   self._bus and self._bus.fileno()) if f is not None]
            try:
                readable, _, _ = select.select(fds, [], [], 0.002)
            except (OSError, ValueError):
                continue   # a descriptor was closed under us by unplug/replug
            with self._lock:
                self._pump(readable, self.clock())

    def _pump(self, readable, now):
        """One relay pass (lock held): read what is ``readable``, deliver
        what is due at ``now`` (s), step the model."""
        stalled = now < self._stalled_until
        self._from_host(readable, now, stalled)
        self._from_firmware(readable, now, stalled)
        self._serve_bus(readable, now)
        self._deliver_to_firmware(now)
        self._deliver_to_host(now)
        self._step_model(now)

    def _from_host(self, readable, now, stalled):
        if self._master is None or self._master not in readable or stalled:
            return
        data = _read(self._master)
        if data is None:
            # EIO: the host has not opened the port; look again in 20 ms.
            self._master_quiet_until = now + 0.02
        elif data:
            self._to_fw.push(data, now)

    def _from_firmware(self, readable, now, stalled):
        if self._proc is None or self._proc.stdout.fileno() not in readable:
            return
        data = _read(self._proc.stdout.fileno())
        if data and not stalled and self._master is not None:
            self._to_host.push(data, now)

    def _serve_bus(self, readable, now):
        """Answer the firmware's bus request with the simulated boards' reply."""
        if self._bus is None or self._bus.fileno() not in readable:
            return
        data = _read(self._bus.fileno())
        reply = self.boards.feed(data, now) if data else b''
        if reply and self.muted is not None and reply[1] == self.muted:
            reply = b''   # one STATE per request: this one is the muted board's
        if reply:
            self._bus.sendall(reply)

    def _deliver_to_firmware(self, now):
        to_fw = self._to_fw.pop_ready(now)
        if not to_fw or self._proc is None:
            return
        if self.record:
            self.host_frames.extend((now, f.topic, f.payload) for f in self._host_parser.feed(to_fw))
        try:
            self._proc.stdin.write(to_fw)
        except (BrokenPipeError, OSError):
            pass

    def _deliver_to_host(self, now):
        to_host = self._to_host.pop_ready(now)
        if not to_host or self._master is None:
            return
        try:
            os.write(self._master, to_host)
        except OSError:
            pass   # nobody has the port open: bytes lost, as on a real line

    def _step_model(self, now):
        """Step the model at the PICO loop rate up to ``now``."""
        while now - self._last_step >= PICO_PERIOD_S:
            self.model.step(PICO_PERIOD_S)
            self._last_step += PICO_PERIOD_S


def _read(fd):
    try:
        return os.read(fd, 4096)
    except (BlockingIOError, InterruptedError):
        return b''
    except OSError:
        return None   # pty master with no slave open: EIO until the host opens it


def build_native_firmware(package_dir, build_dir=None):
    """Build (or bring up to date) the native firmware; return its path.

    Runs ``make -C firmware native``: a no-op when nothing changed. Raises
    RuntimeError with the compiler's output when the build fails. The
    default build folder is one per source tree: two checkouts on one
    machine (worktrees) must never run each other's firmware, and make,
    going by timestamps, would take a newer binary built from other sources.
    """
    import getpass
    import hashlib
    import tempfile
    tree = hashlib.sha1(os.path.realpath(package_dir).encode()).hexdigest()[:12]
    build_dir = build_dir or os.path.join(tempfile.gettempdir(), 'pirate-firmware-%s-%s'
                                          % (getpass.getuser(), tree))
    result = subprocess.run(['make', '-s', '-C', os.path.join(package_dir, 'firmware'),
                             'native', 'BUILD=%s' % build_dir],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if result.returncode != 0:
        raise RuntimeError('native firmware build failed:\n%s' % result.stdout.decode())
    return os.path.join(build_dir, 'pirate_bay_native')
