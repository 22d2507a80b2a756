"""What a person watching a sweep sees: cases done / total, success so far,
the time left; one line rewritten in place on a terminal, plain lines
otherwise (a log file, CI)."""
import time


def clock_text(seconds):
    """'1 h 02 min', '3 min 05 s', '42 s'."""
    seconds = int(round(seconds))
    if seconds >= 3600:
        return '%d h %02d min' % (seconds // 3600, seconds % 3600 // 60)
    if seconds >= 60:
        return '%d min %02d s' % (seconds // 60, seconds % 60)
    return '%d s' % seconds


class Progress(object):
    """Counts finished cases of ``total`` (``before``: the records of the cases finished before a resume)."""

    def __init__(self, total, stream, tty, before=(), clock=time.monotonic):
        already = len({record['key'] for record in before})
        self.total, self.done, self._already = total, already, already
        self.runs = len(before)
        self.succeeded = sum(1 for record in before if record['outcome'] == 'succeeded')
        self._stream, self._tty, self._clock, self._start = stream, tty, clock, clock()
        self._width = 0

    def line(self):
        """The progress line: done / total, success so far, estimated time left."""
        ran = self.done - self._already
        left = (self._clock() - self._start) / ran * (self.total - self.done) if ran else None
        success = ', success %d/%d runs' % (self.succeeded, self.runs) if self.runs else ''
        return '%d/%d cases%s, %s left' % (self.done, self.total, success,
                                           clock_text(left) if left is not None else 'time')

    def finished(self, found):
        """A case finished with the records ``found``."""
        self.done += 1
        self.runs += len(found)
        self.succeeded += sum(1 for record in found if record['outcome'] == 'succeeded')
        what = '; '.join('%s%s: %s' % (record['key'], ' ' + record['variant'] if record['variant'] else '',
                                       record['outcome']) for record in found)
        self._say('%s | %s' % (self.line(), what))

    def note(self, text):
        """A line that stays (a retry, a warning), above the progress line on a terminal."""
        if self._tty:
            self._stream.write('\r' + ' ' * self._width + '\r')
            self._width = 0
        self._stream.write(text + '\n')
        self._stream.flush()

    def _say(self, text):
        if self._tty:
            text = text[:150]
            self._stream.write('\r' + text + ' ' * max(0, self._width - len(text)))
            self._width = len(text)
        else:
            self._stream.write(text + '\n')
        self._stream.flush()

    def end(self):
        if self._tty and self._width:
            self._stream.write('\n')
            self._stream.flush()
            self._width = 0
