"""The safe hold: the one definition of "no motor moves".

Used by the Pirate Server when a PAB ends without success (cancel, timeout,
lost feedback), by the manager on shutdown, and by the Mapper's Stop.

- Bend and front modules: PWM duty 0. The motor is unpowered and the 24:1
  worm gear, which is self-locking, holds the joint where it is *and* keeps
  the series spring loaded, so a clamped part stays clamped. (Torque mode
  with setpoint 0 would actively unload the spring: the clamp would let go.)
  The setpoint is zeroed and sent before the mode changes, so no motor ever
  sees a torque setpoint as a PWM duty.
- Wheels: 0 in their mode (velocity 0 brakes, PWM 0 coasts to a stop).
- Rotation (position mode only): target = its current angle, when known
  and plausible (within the rotation limit), so it stays put instead of
  aligning to 0; a reading beyond the limit is a bad sensor, not a place to
  go: the target it had is kept.
Cameras and LEDs are the operator's (allowed in PAB mode) and are left alone.

Atomic on the wire: the whole hold is written and sent under
the arrays' ``wire_lock``, so no other writer's array can be sent between
its parts or (being older) after it.
"""
from pirate.robot import safety, units

HOLD_PWM = ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv', 'front_tilt')


def safe_hold(setpoint, control, angles=None):
    """Put the robot in the safe hold and send it at once; return the array sent.

    ``angles``: current joint angles (rad) by name, if known.
    """
    with control.wire_lock:
        for joint in HOLD_PWM + ('wheels',):
            setpoint.set(joint, 0)
        rotation = (angles or {}).get('rotation')
        plausible = rotation is not None and safety.rotation_ok(rotation)
        if plausible and control.mode_of('rotation') == 'position':
            setpoint.set('rotation', units.rad_to_rotation(rotation))
        sent = setpoint.publish_now()
        for joint in HOLD_PWM:
            control.set_mode(joint, 'pwm')
        return sent
