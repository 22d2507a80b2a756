"""Manual motion bounded: a motor the panel drives that makes no progress is stopped.

In manual mode the sliders drive the wheels and the bends directly, and no
PAB guard watches them: a wheel slider left up against an end cap turned
the wheels for minutes. :class:`ManualGuard` watches every motor the panel
keeps driving and names the first that has not progressed for
``no_progress_s`` of robot time (config/sequencer.yaml ``manual``):

- the wheels: driven (a non-zero wheel setpoint) while the front and the
  rear odometry do not both advance, together, by ``wheel_progress_mm`` -
  a stalled motor (neither moves), an end cap or a wheel off the wall (one
  part's wheels spin, the other's stand: the robot is one body, its parts
  travel alike);
- a bend or the front module in PWM mode: driven (a non-zero setpoint)
  while its angle does not move by ``joint_progress_rad`` - driven into its
  stop. Torque mode is left alone: a clamp presses on the wall by design.

Pure: the caller passes robot time, what is driven and what is measured.
"""
import collections

#: The joints a PWM setpoint drives against a stop (the rotation runs in position mode only).
PWM_JOINTS = ('front_tilt', 'bend_i', 'bend_ii', 'bend_iii', 'bend_iv')
WHEELS = 'wheels'

Settings = collections.namedtuple('Settings', 'no_progress_s wheel_progress_mm wheel_spread joint_progress_rad')


def settings(common):
    """:data:`Settings` from config/sequencer.yaml's ``manual`` section."""
    manual = common['manual']
    return Settings(float(manual['no_progress_s']), float(manual['wheel_progress_mm']),
                    float(manual['wheel_spread']), float(manual['joint_progress_rad']))


class _Watch(object):
    """One motor: where its measures stood when it last progressed, and when."""

    def __init__(self, now_s, measures):
        self.since_s, self.start = now_s, measures


class ManualGuard(object):
    """Watch the motors the panel drives; :meth:`update` names the stalled ones."""

    def __init__(self, config):
        self.config = config
        self._watches = {}

    def update(self, now_s, driven, angles, odometry):
        """Robot time ``now_s``; ``driven``: the motors with a non-zero manual
        setpoint (``WHEELS`` or :data:`PWM_JOINTS` names); ``angles``
        {joint: rad}; ``odometry`` {'front': mm, 'rear': mm}. Return
        [(motor, why)] for each motor stalled for ``no_progress_s`` (each
        once: it is watched anew when driven again)."""
        stalled = []
        for motor in list(self._watches):
            if motor not in driven:
                del self._watches[motor]
        for motor in driven:
            measures = self._measures(motor, angles, odometry)
            watch = self._watches.get(motor)
            if watch is None or self._progressed(motor, watch.start, measures):
                self._watches[motor] = _Watch(now_s, measures)
            elif now_s - watch.since_s >= self.config.no_progress_s:
                stalled.append((motor, self._why(motor, watch.start, measures, now_s - watch.since_s)))
                self._watches[motor] = _Watch(float('inf'), measures)    # said once while driven
        return stalled

    @staticmethod
    def _measures(motor, angles, odometry):
        if motor == WHEELS:
            return (odometry['front'], odometry['rear'])
        return (angles[motor],)

    def _progressed(self, motor, start, measures):
        moved = [abs(now - then) for now, then in zip(measures, start)]
        if motor != WHEELS:
            return moved[0] >= self.config.joint_progress_rad
        return (min(moved) >= self.config.wheel_progress_mm
                and max(moved) - min(moved) <= self.config.wheel_spread * max(moved))

    def _why(self, motor, start, measures, stalled_s):
        if motor != WHEELS:
            return ('%s driven %.1f s without moving (%.3f rad, stays %.3f): at its stop? Its setpoint is set to 0'
                    % (motor, stalled_s, start[0], measures[0]))
        front, rear = (now - then for now, then in zip(measures, start))
        return ('wheels driven %.1f s without the robot advancing (front odometry %+.0f mm, rear %+.0f mm): an end '
                'cap, a stalled motor or a wheel off the wall? The wheels are stopped' % (stalled_s, front, rear))
