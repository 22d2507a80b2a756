"""The camera pan's angle, reconstructed from what board 20 is sent.

The pan has no encoder (Table B.1 gives board 20 one angle: the tilt's), so
its angle is what its motor has done with the commands it was sent: in
position mode it turns towards the setpoint at the drive's top speed, in
PWM mode at that speed times duty / 256, between its stops; while the
boards are stopped (before PLAY, after STOP, or a single stop or calibrate
at the pan) it stays where it is. Speed and stops are the estimates the
twin moves it by (config/twin.yaml ``camera``). Pure.
"""
import os

import yaml

from pirate import paths
from pirate.robot import safety, tables, units

PAN = tables.element('camera_pan').index
COMMAND = tables.element('rear_module').index
PLAY, STOP = safety.COMMAND_CODES['play'], safety.COMMAND_CODES['stop']
POSITION, PWM = safety.MODE_CODES['position'], safety.MODE_CODES['pwm']


def drive_config(path=os.path.join(paths.CONFIG_DIR, 'twin.yaml')):
    """(top speed rad/s, (low, high) stops rad) of the camera drive."""
    with open(path) as stream:
        camera = yaml.safe_load(stream)['camera']
    return float(camera['no_load_rad_s']), tuple(float(v) for v in camera['range_rad'])


class PanEstimate(object):
    """The pan's angle (rad) from the setpoint and control arrays sent."""

    def __init__(self, top_rad_s, stops, angle=0.0):
        self.top_rad_s, self.stops = top_rad_s, stops
        self._angle, self._since = angle, None
        self._mode, self._counts = None, 0
        self.running = False

    def angle(self, now):
        """Where the pan is at ``now`` (s, the clock :meth:`command` is given)."""
        if self._since is None or not self.running or now <= self._since:
            return self._angle
        step = self.top_rad_s * (now - self._since)
        if self._mode == POSITION:
            target = units.encoder_to_rad(self._counts) - self._angle
            angle = self._angle + max(-step, min(step, target))
        elif self._mode == PWM:
            angle = self._angle + step * max(-1.0, min(1.0, self._counts / float(safety.DUTY_MAX)))
        else:
            angle = self._angle
        return max(self.stops[0], min(self.stops[1], angle))

    def command(self, setpoints, modes, now):
        """The arrays as sent at ``now``; the pan moved as the last ones said until then."""
        self._angle = self.angle(now)
        self._since = now
        if modes[COMMAND] == PLAY:
            self.running = True
        elif modes[COMMAND] == STOP:
            self.running = False
        self._mode, self._counts = modes[PAN], setpoints[PAN]
