"""A fast fake of PIRATE for unit tests: NOT physics, NOT the simulated robot.

The simulated robot is the physics twin (:mod:`pirate.sim.twin`, chosen by
``robot:=sim`` and ``SimHarness()``). This module is the old single
cross-section model, kept only where a unit test needs a fast deterministic
robot (many-roll sweeps, property tests); no launch file, node or rostest
builds it. Its constants
below were FITTED to the report's own tables (6.1, 6.2, 6.5) so that it
reproduces them; they are not measured properties of PIRATE, and agreement
with the report proves nothing about the robot.

No ROS here: :class:`FakeRobot` takes the three command arrays exactly as
the Mega receives them (laptop convention, SPEC 3) and produces one raw Small
State per board (Table B.1). The guard tables are never read.

Geometry of a clamp (report 2.4.1.1, eq 2.1, Fig 4.6)
-----------------------------------------------------
A clamp is an inverted V of two bend modules. The part beyond the inner
module lies on the bottom of the pipe, the inner module rises by ``e`` to the
apex wheel touching the top, the outer module falls back to the bottom. Both
ends on the bottom give outer = -2e, inner = +e (the report's outer/inner
ratio, Table 6.5: -0.84 / 0.43). The apex reaches the wall when

    sin(e) = (D_eff - Dw) / L

with Dw the wheel diameter and L the axle-to-axle distance between two
wheels across a joint. When the robot lies at roll ``psi`` (Fig 4.7) its
bending plane passes at d = (R - h) |cos psi| from the pipe axis and the
wall is a chord away: D_eff = 2 sqrt(R^2 - d^2) (the chord of SPEC 2).

Constants and what they were fitted to (not physics)
----------------------------------------------------
- MODULE_LENGTH 0.09 m, WHEEL_DIAMETER 0.046 m: report 2.4.1.1.
- AXLE_PITCH 0.102 m: module length plus the 12 mm joint housing. Fitted
  once: 90 mm gives outer -0.89 / inner 0.45 rad (Table 6.5 averages
  -0.835 / 0.43, within 0.06), and the same constant, unchanged, gives
  110 mm: -1.36 / 0.68, beyond the report's 110 mm guards (-1.25 / 0.65).
- SIDE_HALF_WIDTH 0.027 m: distance from the wall to the robot's axis when it
  lies on its side (half a module's width). With it a robot lying on its side
  in 90 mm reaches -0.73 / 0.37, past the custom-clamp guards (-0.68 / 0.33,
  Table 5.3) but not the full-clamp ones (-0.77 / 0.35), as the report found.
- Bend speed: a torque-controlled bend closes at
  BEND_MAX_RAD_S * tanh(|setpoint| / BEND_SETPOINT_SCALE); the saturation is
  that of a torque loop driving a worm gear against friction. Fitted to the
  report's timings: a clamp (setpoint 256, to the -0.77 guard) takes 3.9 s
  and an unclamp (setpoint -100) 6.5 s, which makes the simple clamp straight
  10.8 s (Table 6.1) and the test mission 28 s (section 6.5).
- FRONT_RAD_S_PER_DUTY: move front at PWM 32 reaches the 0.4 rad guard in
  2.9 s (the rest of the 10.77 s of Table 6.1).
- ROTATION_MAX_RAD_S 0.3, ROTATION_GAIN 3 /s: the rotational module's
  position loop; a 0.1 rad re-adjust takes about 0.5 s, so the nominal
  re-adjust totals about 23 s (report: about 25 s).
- Wheels: first-order lag WHEEL_TAU_S 0.05 s to the velocity setpoint (the
  PICO's 50 Hz velocity loop settles in a few samples).
- Worm gears (24:1) are self-locking: a motor with no drive (PWM 0), or a
  stopped board, holds its joint where it is. A bend in torque mode at
  setpoint 0 is the exception: the torque loop makes it compliant, and an
  inner bend is closed by the outer one's push while the outer is driven
  closed (``_follow_outer``). A held
  bend keeps its spring's deflection too: a clamp held at PWM 0 (the safe
  hold) still reads as pressing the wall, as in the physics twin.
- Spring: effort in contact = commanded torque, TORQUE_MNM_PER_COUNT mNm per
  setpoint count (256 counts ~ 400 mNm, the peaks of Figs 6.2, 6.4),
  read back through the spring encoder (units.mnm_to_spring).

Which part turns (report 4.7.2.2, Table 4.5)
--------------------------------------------
The rotation angle is theta = rear_roll - front_roll. Turning it turns the
part that is not clamped: the rear's roll (what the IMU reports) changes only
when the front is clamped and the rear is free. With both clamped the motor
stalls; with neither clamped the lighter front part turns.
"""
import math
import random

from pirate.robot import safety, tables, units
from pirate.sim.latch import CODE, CommandLatch

MODULE_LENGTH = 0.09
WHEEL_DIAMETER = 0.046
AXLE_PITCH = 0.102
SIDE_HALF_WIDTH = 0.027
BEND_MAX_RAD_S = 0.23
BEND_SETPOINT_SCALE = 200.0
BEND_STRAIGHT_PLAY = 0.02        # rad a bend can go past straight into the floor
FRONT_RAD_S_PER_DUTY = 0.0043
FRONT_RANGE = (-0.05, 1.2)       # rad, mechanical stops of the front module
CAMERA_RAD_S_PER_DUTY = 0.01
CAMERA_RANGE = (-1.5, 1.5)
POSITION_GAIN = 3.0              # 1/s, PICO position loops (camera, front, rotation)
POSITION_MAX_RAD_S = 0.5
ROTATION_MAX_RAD_S = 0.3
ROTATION_GAIN = 3.0
WHEEL_TAU_S = 0.05
WHEEL_PWM_MAX_MM_S = 200.0
TORQUE_MNM_PER_COUNT = 1.6
CLAMP_TOLERANCE = 0.03           # rad from the wall that still counts as clamped
IMU_NOISE_COUNTS = 40.0
ANGLE_NOISE_COUNTS = 1.0


#: The two clamps: (outer bend, inner bend, the part they belong to).
CLAMPS = {'front': ('bend_i', 'bend_ii'), 'rear': ('bend_iv', 'bend_iii')}


def clamp_half_angle(pipe_diameter_m, roll):
    """Inner-bend angle ``e`` (rad) at which a clamp's apex meets the wall.

    ``roll`` is the part's orientation (Fig 4.7); off upright the bending
    plane misses the pipe axis and only a chord of the pipe is available.
    """
    radius = pipe_diameter_m / 2.0
    offset = (radius - SIDE_HALF_WIDTH) * abs(math.cos(roll))
    chord = 2.0 * math.sqrt(max(radius ** 2 - offset ** 2, 0.0))
    span = (chord - WHEEL_DIAMETER) / AXLE_PITCH
    return math.asin(min(max(span, 0.0), 1.0))


def _approach(value, target, max_step):
    """Move ``value`` towards ``target`` by at most ``max_step``."""
    return value + max(-max_step, min(max_step, target - value))


class FakeRobot(CommandLatch):
    """The fake robot (fitted, not physics): joint angles, rolls, wheel travel, in SI units."""

    def __init__(self, pipe_diameter=90, orientation=math.pi / 2, joints=None, seed=None):
        self.pipe_diameter_m = pipe_diameter / 1000.0
        self.rear_roll = float(orientation)
        self.joint_angles = {name: 0.0 for name in tables.JOINT_NAMES}
        self.joint_angles.update(joints or {})
        self.effort = {name: 0.0 for name in tables.BEND_JOINTS}
        self.wheel_mm_s = 0.0
        self.odometry_mm = 0.0
        self.roll_rate = 0.0
        CommandLatch.__init__(self)
        self._rng = random.Random(seed) if seed is not None and seed >= 0 else None

    # --- derived state -----------------------------------------------------
    @property
    def rotation(self):
        """Rotation angle theta, rad (rear roll minus front roll)."""
        return self.joint_angles['rotation']

    @property
    def front_roll(self):
        """Roll of the front part, rad (Fig 4.7)."""
        return self.rear_roll - self.rotation

    def roll_of(self, part):
        """Roll of 'front' or 'rear' part."""
        return self.front_roll if part == 'front' else self.rear_roll

    def contact_angle(self, part):
        """Inner-bend angle of ``part``'s clamp when its apex meets the wall."""
        return clamp_half_angle(self.pipe_diameter_m, self.roll_of(part))

    def clamped(self, part):
        """True when both bends of ``part`` press the pipe wall."""
        outer, inner = CLAMPS[part]
        e = self.contact_angle(part)
        return (self.joint_angles[outer] <= -2 * e + CLAMP_TOLERANCE
                and self.joint_angles[inner] >= e - CLAMP_TOLERANCE)

    # --- dynamics ----------------------------------------------------------
    def step(self, dt):
        """Advance the robot by ``dt`` seconds (one or more PICO samples)."""
        was = {part: self.clamped(part) for part in CLAMPS}
        for part in CLAMPS:
            for name in CLAMPS[part]:
                self._step_bend(name, part, dt)
        self._step_positional('front_tilt', FRONT_RAD_S_PER_DUTY, FRONT_RANGE, dt)
        self._step_positional('camera_tilt', CAMERA_RAD_S_PER_DUTY, CAMERA_RANGE, dt)
        self._step_positional('camera_pan', CAMERA_RAD_S_PER_DUTY, CAMERA_RANGE, dt)
        self._step_rotation(was, dt)
        self._step_wheels(was, dt)

    def _step_bend(self, name, part, dt):
        counts = self._drive(name)
        mode = self._mode(name)
        if counts is None or mode not in (CODE['pwm'], CODE['torque'], CODE['current'],
                                          safety.COMMAND_CODES['torque_limit']) \
                or (mode == CODE['pwm'] and counts == 0):
            return  # stopped, PWM 0, or a mode the bend has not got: the worm holds
                    # the joint and its spring's deflection (the effort reads on)
        if mode != CODE['pwm']:
            counts = self._torque_counts(name, counts)
        if counts == 0 and mode != CODE['pwm'] and name == CLAMPS[part][1]:
            if self._outer_closing(part):
                self._follow_outer(name, part)
            else:
                self.effort[name] = 0.0     # compliant, and nothing pushes it
            return
        speed = BEND_MAX_RAD_S * math.tanh(abs(counts) / BEND_SETPOINT_SCALE)
        direction = -1.0 if counts > 0 else 1.0   # +setpoint closes outer (-) and opens inner
        e = self.contact_angle(part)
        outer = name == CLAMPS[part][0]
        low, high = (-2 * e, BEND_STRAIGHT_PLAY) if outer else (-BEND_STRAIGHT_PLAY, e)
        angle = self.joint_angles[name]
        target = angle + direction * speed * dt
        self.joint_angles[name] = min(max(target, low), high)
        pressing = counts != 0 and (target < low or target > high)
        self.effort[name] = counts * TORQUE_MNM_PER_COUNT if pressing else 0.0

    def _outer_closing(self, part):
        """True while ``part``'s outer bend is driven closed (torque toward the wall).

        Only then does it push a compliant inner bend along. Without this
        rule an inner bend snapped to half the outer's angle in any cycle it
        sat at torque 0 - e.g. the one cycle between the zero setpoint and
        the PWM mode of a worm hold after Home's unclamp - and the part read
        as partly clamped after Home (seq_mission under load).
        """
        outer = CLAMPS[part][0]
        counts = self._drive(outer)
        return counts is not None and counts > 0 and self._mode(outer) != CODE['pwm']

    def _follow_outer(self, name, part):
        """An inner bend at zero torque is compliant: the outer bend's push
        closes the V until both ends rest on the floor (inner = -outer / 2),
        at most up to the wall. This is why the report's inner bends end near
        0.43 rad after the clamp has released them (Table 6.5)."""
        closure = -self.joint_angles[CLAMPS[part][0]] / 2.0
        self.joint_angles[name] = max(self.joint_angles[name], min(closure, self.contact_angle(part)))
        self.effort[name] = 0.0

    def _step_positional(self, name, rad_s_per_duty, limits, dt):
        """A PWM/position joint: camera tilt and pan, front module."""
        counts = self._drive(name)
        if counts is None:
            return
        angle = self.joint_angles[name]
        mode = self._mode(name) if tables.element(name).index < tables.CONTROL_SIZE else CODE['pwm']
        if mode == CODE['position']:
            target = units.encoder_to_rad(counts)
            step = min(POSITION_GAIN * abs(target - angle), POSITION_MAX_RAD_S) * dt
            angle = _approach(angle, target, step)
        elif mode == CODE['pwm']:
            angle += counts * rad_s_per_duty * dt
        self.joint_angles[name] = min(max(angle, limits[0]), limits[1])

    def _step_rotation(self, was_clamped, dt):
        counts = self._drive('rotation')
        self.roll_rate = 0.0
        if counts is None or self._mode('rotation') != CODE['position']:
            return
        if was_clamped['front'] and was_clamped['rear']:
            return  # both parts wedged in the pipe: the motor stalls
        theta = self.rotation
        target = units.rotation_to_rad(counts)
        step = min(ROTATION_GAIN * abs(target - theta), ROTATION_MAX_RAD_S) * dt
        new_theta = _approach(theta, target, step)
        if was_clamped['front'] and not was_clamped['rear']:
            self.rear_roll += new_theta - theta        # the rear part turns
            self.roll_rate = (new_theta - theta) / dt
        self.joint_angles['rotation'] = new_theta     # otherwise the front turns

    def _step_wheels(self, was_clamped, dt):
        counts = self._drive('wheels')
        if counts is None:
            target = 0.0
        elif self._mode('wheels') == CODE['velocity']:
            target = units.wheel_counts_to_mm_s(counts)
        else:
            target = counts / float(safety.DUTY_MAX) * WHEEL_PWM_MAX_MM_S
        self.wheel_mm_s += (target - self.wheel_mm_s) * min(dt / WHEEL_TAU_S, 1.0)
        if was_clamped['front'] or was_clamped['rear']:
            self.odometry_mm += self.wheel_mm_s * dt   # traction only while clamped

    # --- outputs -----------------------------------------------------------
    def _noise(self, sigma):
        return self._rng.gauss(0.0, sigma) if self._rng else 0.0

    def _angle_counts(self, name):
        if name == 'rotation':
            return units.rad_to_rotation(self.joint_angles[name])
        return units.rad_to_encoder(self.joint_angles[name]) + int(round(self._noise(ANGLE_NOISE_COUNTS)))

    def small_state(self, board):
        """The nine raw int16 elements of ``board``'s Small State (Table B.1)."""
        if board not in tables.BOARDS:
            raise KeyError('no PICO board %r' % board)
        data = [0] * tables.SMALL_STATE_SIZE
        if board in tables.DRIVE_BOARDS:
            data[tables.SS_ODOMETRY] = units.wrap_int16(self.odometry_mm / units.WHEEL_MM_PER_COUNT)
            data[tables.SS_VELOCITY] = units.mm_s_to_wheel_counts(self.wheel_mm_s)
            data[tables.SS_DRIVE_LOAD] = int(round(self.wheel_mm_s / WHEEL_PWM_MAX_MM_S * safety.DUTY_MAX))
        if board == tables.IMU_BOARD:
            g_y, g_z = units.roll_to_gravity(self.rear_roll)
            data[tables.SS_IMU_Y] = int(round(g_y + self._noise(IMU_NOISE_COUNTS)))
            data[tables.SS_IMU_Z] = int(round(g_z + self._noise(IMU_NOISE_COUNTS)))
            data[tables.SS_IMU_U] = int(round(math.degrees(self.roll_rate) * units.IMU_COUNTS_PER_DEG_S))
            return [units.wrap_int16(v) for v in data]
        for joint in tables.JOINTS:
            if joint.board == board:
                data[tables.SS_ANGLE] = self._angle_counts(joint.name)
                if joint.has_spring:
                    data[tables.SS_BEND_LOAD] = units.mnm_to_spring(self.effort[joint.name])
                    data[tables.SS_TORQUE] = self._torque_output(joint.name)
        return [units.wrap_int16(v) for v in data]

    def _torque_output(self, name):
        counts = self._drive(name)
        return 0 if counts is None else max(-safety.DUTY_MAX, min(safety.DUTY_MAX, counts))
