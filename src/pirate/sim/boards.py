"""The PICO boards' motor loops, as the physics twin runs them (Table 2.1).

Each board turns its latched mode and setpoint into what its motor does,
every PICO sample (50 Hz), from what the board itself senses. The results
are MuJoCo actuator targets (pirate.sim.twin): a bend's worm-side angle
(the series spring's far end), a gear motor's output angle, the rotation
target, a wheel's speed. Pure: no MuJoCo, no ROS; constants from
config/twin.yaml, their sources in config/twin_sources.yaml.
"""
import math

from pirate.robot import safety, units
from pirate.sim.latch import CODE

DUTY_MAX = float(safety.DUTY_MAX)
TORQUE_MODES = (CODE['torque'], CODE['current'], safety.COMMAND_CODES['torque_limit'])


def _clip(value, low, high):
    return max(low, min(high, value))


class BendBoard(object):
    """A bend module: motor, self-locking 87:1 worm, series spring (2.4.3.1).

    ``worm`` is the spring's driven end in joint radians: only the motor
    moves it (the worm gear is not back-drivable), so with no duty the joint
    is held by the spring. A positive duty turns the worm towards negative
    joint angles (a positive setpoint closes an outer bend, SPEC 7). Torque
    mode is the board's loop on the spring deflection it measures: setpoint
    and feedback in spring-encoder counts, limited by the torque limit.
    """

    def __init__(self, cfg, angle=0.0):
        self.worm = angle
        self.spring = cfg['spring_nm_per_rad']
        self.no_load = cfg['no_load_rad_s']
        self.stall = cfg['stall_nm']
        self.kp = cfg['torque_kp_duty_per_count']
        self.duty = 0.0

    def effort_mnm(self, joint):
        """Spring torque felt at the joint, mNm, positive when it pushes
        the joint negative (the direction a positive setpoint drives)."""
        return -self.spring * (self.worm - joint) * 1000.0

    def spring_counts(self, joint):
        """What the board's spring encoder reads (raw counts)."""
        return units.mnm_to_spring(self.effort_mnm(joint))

    def update(self, mode, counts, limit, joint, dt):
        """One PICO sample: set the duty, turn the worm."""
        if counts is None:
            self.duty = 0.0
        elif mode == CODE['pwm']:
            self.duty = float(counts)
        elif mode in TORQUE_MODES:
            target = counts if limit is None else _clip(counts, -limit, limit)
            self.duty = _clip(self.kp * (target - self.spring_counts(joint)), -DUTY_MAX, DUTY_MAX)
        else:
            self.duty = 0.0
        direction = 1.0 if self.duty > 0 else -1.0
        resisting = max(0.0, direction * self.effort_mnm(joint) / 1000.0)
        speed = self.no_load * max(0.0, abs(self.duty) / DUTY_MAX - resisting / self.stall)
        self.worm -= direction * speed * dt
        return self.worm


class GearBoard(object):
    """A geared joint with PWM and position modes: front tilt, camera tilt
    and pan. The output is stiffly held where the motor put it."""

    def __init__(self, cfg, angle=0.0, position_kp=2.0):
        self.angle = angle
        self.no_load = cfg['no_load_rad_s']
        self.low, self.high = cfg.get('range_rad', (-math.pi, math.pi))
        self.kp = cfg.get('position_kp_duty_per_count', position_kp)

    def update(self, mode, counts, joint, dt):
        """One PICO sample; ``joint`` is the measured angle (rad)."""
        if counts is None:
            duty = 0.0
        elif mode == CODE['position']:
            error = counts - units.rad_to_encoder(joint)
            duty = _clip(self.kp * error, -DUTY_MAX, DUTY_MAX)
        elif mode == CODE['pwm']:
            duty = float(counts)
        else:
            duty = 0.0
        self.angle = _clip(self.angle + self.no_load * duty / DUTY_MAX * dt, self.low, self.high)
        return self.angle


class RotationBoard(object):
    """The rotational module: position mode only; its target moves at the
    motor's top speed; the torque it can exert (MuJoCo actuator limit)
    decides which part turns. Encoder zeroed at start-up (SPEC 2)."""

    def __init__(self, cfg, angle=0.0):
        self.target = angle
        self.zero = angle
        self.max_rad_s = cfg['max_rad_s']

    def update(self, mode, counts, dt):
        if counts is not None and mode == CODE['position']:
            goal = units.rotation_to_rad(counts) + self.zero
            self.target += _clip(goal - self.target, -self.max_rad_s * dt, self.max_rad_s * dt)
        return self.target


class WheelBoard(object):
    """A drive board's in-wheel motor: velocity mode (counts per 20 ms,
    the board's PID loop on its encoder's speed, 2.4.3.2) or PWM (a DC
    motor: duty sets its no-load speed, back-EMF its damping; duty 0 lets
    the wheel roll, slowed only by that damping).

    The velocity loop is a PI (the PICO boards are the report's "local PID
    controllers", 1.1): the proportional part is the MuJoCo servo's gain,
    the integral part shifts the servo's target by ``ki / kv`` times the
    integrated speed error, so a wheel under steady load (bearing friction,
    the drag of the shells) still turns at its setpoint; the integral is
    bounded by the motor's stall torque (anti-windup).
    """

    def __init__(self, cfg, radius, sign):
        self.pwm_mm_s = cfg['pwm_mm_s_at_256']
        self.radius, self.sign = radius, sign
        self.loop_kv = cfg['kv_nms_per_rad']
        self.loop_ki = cfg['ki_nm_per_rad']
        self.stall = cfg['stall_nm']
        self.motor_kv = self.stall / (self.pwm_mm_s / 1000.0 / radius)
        self.integral = 0.0                  # rad of speed error integrated (the wheel's axle)

    def update(self, mode, counts, rate, dt):
        """One PICO sample with the wheel's measured ``rate`` (rad/s about
        its axle): (servo target rad/s, servo gain N m s/rad)."""
        if counts is not None and mode == CODE['velocity']:
            target = self.sign * units.wheel_counts_to_mm_s(counts) / 1000.0 / self.radius
            bound = self.stall / self.loop_ki
            self.integral = _clip(self.integral + (target - rate) * dt, -bound, bound)
            return target + self.loop_ki / self.loop_kv * self.integral, self.loop_kv
        self.integral = 0.0
        if counts is not None and mode == CODE['pwm']:
            mm_s = counts / DUTY_MAX * self.pwm_mm_s
        else:
            mm_s = 0.0                           # stopped board: the motor's damping only
        return self.sign * mm_s / 1000.0 / self.radius, self.motor_kv
