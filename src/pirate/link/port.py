"""The serial port under a rosserial session: open, read, write, reconnect.

No ROS here; :mod:`.host` owns one :class:`SerialLink` and calls it from its
reader and writer threads. A port that disappears (cable unplugged, pty
closed) raises inside pyserial; the link closes itself and the next
:meth:`SerialLink.ensure_open` tries again, so the node never needs a
restart.
"""
import threading

import serial


class SerialLink(object):
    """A pyserial port that may come and go; byte counters for diagnostics."""

    def __init__(self, port, baud, read_timeout=0.02, write_timeout=0.2):
        self.port_name = port
        self.baud = baud
        self._read_timeout = read_timeout
        self._write_timeout = write_timeout
        self._port = None
        self._write_lock = threading.Lock()
        self.bytes_in = 0
        self.bytes_out = 0
        self.last_error = None

    @property
    def is_open(self):
        return self._port is not None

    def ensure_open(self):
        """Open the port if closed; True when open. Never raises."""
        if self._port is not None:
            return True
        try:
            self._port = serial.Serial(self.port_name, self.baud,
                                       timeout=self._read_timeout,
                                       write_timeout=self._write_timeout)
        except (serial.SerialException, OSError, ValueError) as error:
            self.last_error = str(error)
            return False
        self.last_error = None
        return True

    def close(self):
        """Close and forget the port (idempotent)."""
        port, self._port = self._port, None
        if port is not None:
            try:
                port.close()
            except (serial.SerialException, OSError):
                pass

    def read(self):
        """Bytes available now (waits up to the read timeout); None if the port died."""
        port = self._port
        if port is None:
            return None
        try:
            data = port.read(max(1, port.in_waiting))
        except (serial.SerialException, OSError, TypeError) as error:
            # TypeError: pyserial reading a port closed under it by close()
            self.last_error = str(error)
            self.close()
            return None
        self.bytes_in += len(data)
        return data

    def write(self, data):
        """Write all of ``data``; False (and the port closed) if it failed."""
        if not data:
            return True
        with self._write_lock:
            port = self._port
            if port is None:
                return False
            try:
                port.write(data)
            except (serial.SerialException, OSError) as error:
                self.last_error = str(error)
                self.close()
                return False
        self.bytes_out += len(data)
        return True

    def discard_output(self):
        """Throw away bytes written but not yet sent (stale after a stall)."""
        with self._write_lock:
            port = self._port
            if port is not None:
                try:
                    port.reset_output_buffer()
                except (serial.SerialException, OSError, AttributeError):
                    pass
