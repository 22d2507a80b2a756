"""Sensing a junction ahead from what the robot senses (report 4.7.4).

"Drive until the front part loses traction": the clamped leading V (the
front's, or the rear's when the robot drives backwards) presses
its apex wheel on one wall and its two end wheels on the other; where the
wall under the apex goes away (the open side of a T-joint, the far side of
a mitre bend) the V's spring has nothing to press against. The clamp's
torque loop then closes the V: the outer bend (Bend I) turns further
toward its clamp side and its spring unloads. Either one is the junction:

- the outer spring drops below ``spring_clamp_mnm`` (the clamp state's own
  threshold for "pressing the wall", :mod:`pirate.sequencer.clamp_state`);
- the outer bend closes more than ``close_rad`` within the last
  ``close_window_mm`` of odometry: at a T-joint's hole it closed 0.048 rad
  within 10 mm (twin, 90 mm); clamped upright in a straight pipe it held
  within 0.003 rad, but clamped on a side it crept 0.066 rad closed over
  250 mm of driving (twin, clamp_sideways row), so the angle is
  compared with where it was a short way back, not at the start.

One of them must hold for ``samples`` consecutive robot states, so one
noisy sample is not a junction. Nothing here reads the twin's ground truth:
only the joint angles, spring efforts and odometry of a
:class:`pirate.state.feed.RobotView`. Pure.
"""
import collections

from pirate.sequencer import clamp_state
from pirate.sequencer.guards import CLAMP_BENDS

#: Where the junction was sensed: odometry (mm) and robot time (s) of the
#: first state of the run of ``samples`` that fired, and why.
Sensed = collections.namedtuple('Sensed', 'odometry stamp why')


class JunctionSensor(object):
    """Watches the front V while the robot searches; :meth:`update` per state.

    ``guards``: :class:`pirate.sequencer.guards.Guards` (its ``junction``
    row and ``clamp_state`` row); ``start``: the RobotView when the search
    began; ``part``: the leading part ('front' / 'rear'), whose V it watches.
    The window is odometry travelled either way.
    """

    def __init__(self, guards, start, part='front'):
        row = guards.row('junction')
        self.close_rad = float(row['close_rad'])
        self.window_mm = float(row['close_window_mm'])
        self.samples = int(row['samples'])
        self.spring_mnm = clamp_state.spring_clamp_mnm(guards)
        self.outer = CLAMP_BENDS[part][0]
        self.sign = 1 if guards.pair('clamp', part).outer.setpoint > 0 else -1
        self._track = [(start.odometry, start.angles[self.outer])]   # (mm, rad), oldest first
        self._run = []
        self.sensed = None

    def why(self, view):
        """Why ``view`` looks like a junction ahead, or '' when it does not."""
        spring = (view.efforts or {}).get(self.outer, 0.0) * self.sign
        closed = (self._reference(view) - view.angles[self.outer]) * self.sign
        reasons = []
        if spring < self.spring_mnm:
            reasons.append('%s spring %.0f mNm < %.0f mNm' % (self.outer, spring, self.spring_mnm))
        if closed > self.close_rad:
            reasons.append('%s closed %.3f rad > %.3f rad within %.0f mm'
                           % (self.outer, closed, self.close_rad, self.window_mm))
        return ' and '.join(reasons)

    def _reference(self, view):
        """The outer bend's angle ``close_window_mm`` of odometry before ``view``
        (the oldest one kept while the search has not gone that far)."""
        while len(self._track) > 1 and abs(view.odometry - self._track[1][0]) >= self.window_mm:
            self._track.pop(0)
        return self._track[0][1]

    def update(self, view):
        """Feed one robot state; True once the junction is sensed (then stays True)."""
        if self.sensed is not None:
            return True
        why = self.why(view)
        self._track.append((view.odometry, view.angles[self.outer]))
        self._run = self._run + [(view, why)] if why else []
        if len(self._run) >= self.samples:
            first, _ = self._run[0]
            self.sensed = Sensed(first.odometry, first.stamp, why)
        return self.sensed is not None
