"""Unit conversions between the robot's raw counts and SI units (SPEC 2-3).

Each constant says where it comes from. Pure functions, no ROS.
"""
import math

#: AS5055 absolute magnetic encoder: 12 bit, 4096 counts per turn (SPEC 2).
ENCODER_COUNTS_PER_RAD = 4096.0 / (2.0 * math.pi)
#: Rotational module incremental encoder (author's code, SPEC 3).
ROTATION_COUNTS_PER_RAD = 2133.33
#: Wheel odometry resolution (author's code, SPEC 3).
WHEEL_MM_PER_COUNT = 0.083
#: PICO control loops sample at 50 Hz (SPEC 2): a velocity setpoint is
#: counts per sample.
PICO_SAMPLE_S = 0.02
#: Bend drive: spring-to-joint gear 58:16; the spring sensor turns 58/16
#: times the joint's deflection (report 2.4.3.1).
SPRING_TO_JOINT = 58.0 / 16.0
#: Joint-felt spring constant, mNm per degree (report 2.4.3.1).
SPRING_MNM_PER_DEG = 41.6
#: IMU scale: accelerometer counts per g and gyro counts per deg/s
#: (a +-2 g / +-250 deg/s MEMS IMU, 16-bit). The Mega forwards raw counts.
IMU_COUNTS_PER_G = 16384.0
IMU_COUNTS_PER_DEG_S = 131.0

INT16_MIN = -32768


def encoder_to_rad(counts):
    """AS5055 counts -> rad."""
    return counts / ENCODER_COUNTS_PER_RAD


def rad_to_encoder(rad):
    """rad -> AS5055 counts (rounded)."""
    return int(round(rad * ENCODER_COUNTS_PER_RAD))


def rotation_to_rad(counts):
    """Rotational module counts -> rad."""
    return counts / ROTATION_COUNTS_PER_RAD


def rad_to_rotation(rad):
    """rad -> rotational module counts (rounded)."""
    return int(round(rad * ROTATION_COUNTS_PER_RAD))


def mm_s_to_wheel_counts(mm_s):
    """Wheel speed mm/s -> velocity setpoint, counts per 20 ms PICO sample."""
    return int(round(mm_s / WHEEL_MM_PER_COUNT * PICO_SAMPLE_S))


def wheel_counts_to_mm_s(counts):
    """Velocity in counts per 20 ms sample -> mm/s."""
    return counts * WHEEL_MM_PER_COUNT / PICO_SAMPLE_S


def wheel_speed_mm_s(mm_s):
    """The speed (mm/s) the wheels turn at when asked for ``mm_s``: the setpoint is
    whole counts per PICO sample, so 10 mm/s turns them at 8.3 mm/s. Time bounds
    and watchdogs of a drive are planned with this, not with the asked speed."""
    return wheel_counts_to_mm_s(mm_s_to_wheel_counts(mm_s))


def odometry_to_mm(counts):
    """Wheel odometry counts -> mm."""
    return counts * WHEEL_MM_PER_COUNT


def spring_to_mnm(counts):
    """Spring encoder deflection (counts) -> joint effort in mNm."""
    joint_deg = math.degrees(encoder_to_rad(counts)) / SPRING_TO_JOINT
    return joint_deg * SPRING_MNM_PER_DEG


def mnm_to_spring(mnm):
    """Joint effort in mNm -> spring encoder deflection (counts, rounded)."""
    joint_rad = math.radians(mnm / SPRING_MNM_PER_DEG)
    return rad_to_encoder(joint_rad * SPRING_TO_JOINT)


def roll_to_gravity(roll):
    """Orientation (rad, Fig 4.7) -> accelerometer (g_y, g_z) counts.

    The accelerometer on the rear part feels 1 g pointing up in the world:
    g_z (the robot's up axis) = g sin(roll), g_y (its lateral axis, towards
    the side it lies on at roll 0) = g cos(roll). Upright (pi/2) is all z.
    """
    return (IMU_COUNTS_PER_G * math.cos(roll), IMU_COUNTS_PER_G * math.sin(roll))


def gravity_to_roll(g_y, g_z):
    """Accelerometer (y, z) counts -> orientation in [-pi/2, 3pi/2) (Fig 4.7).

    The range is chosen so that the working region 0..pi (lying on the right
    side, upright, lying on the left side) never wraps.
    """
    roll = math.atan2(g_z, g_y)
    if roll < -math.pi / 2:
        roll += 2 * math.pi
    return roll


def wrap_int16(value):
    """Wrap an integer into int16 range, as a 16-bit counter on the PICO does."""
    return (int(value) - INT16_MIN) % 65536 + INT16_MIN


def unwrap_int16(previous, raw):
    """Smallest signed step from int16 ``previous`` to int16 ``raw``."""
    return wrap_int16(raw - previous)
