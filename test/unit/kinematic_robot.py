"""A robot that only rolls and rotates: the report's kinematics (Table 4.5).

The rotational module turns the part that is not clamped (theta = rear
roll - front roll); clamps and unclamps set the bend angles to their guards
and the outer spring to pressing. Feed and primitives in one object, for
running a PAB's table on the logic alone (no physics, no timing).
"""
from pirate.robot import safety
from pirate.state.feed import RobotView, TimedOut
from pirate.sequencer import clamp_state
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.primitives import Refused, clamp_name, report_kind
from pirate.sequencer.server import PabContext

BOOK = GuardBook(*load_files())
PRESS_MNM = 241.0       # the outer spring on the wall; measurements.md#clamp-spring-thresholds
#: Outer bend angle (rad) where the front V meets the walls with the front
#: part lying on a side, per pipe diameter: the V spans the chord there,
#: not the diameter (twin, 90 mm, bench/pab_clamp_probe 90 150 left:
#: Bend I -0.638 rad, spring 240 mNm; measurements.md#front-custom-sideways).
#: A clamp whose guard lies beyond it is not reached.
FRONT_WALL_ON_SIDE_RAD = {90: -0.638}


class KinematicRobot(object):
    """Feed and primitives of a robot that only rolls and rotates."""

    def __init__(self, rear_roll, rotation, front_tilt, pipe_diameter=90):
        self.guards = BOOK.for_diameter(pipe_diameter)
        self.front_wall_on_side = FRONT_WALL_ON_SIDE_RAD.get(pipe_diameter)
        self.rear, self.rotation = rear_roll, rotation
        self.front = rear_roll - rotation
        self.angles = {j: 0.0 for j in ('front_tilt', 'bend_i', 'bend_ii', 'rotation', 'bend_iii', 'bend_iv')}
        self.angles.update(rotation=rotation, front_tilt=front_tilt)
        self.efforts = {}
        self.clamped = {'front': False, 'rear': False}
        self.executed = []
        self.unclamp_rows = []          # the guard row each unclamp was given (None: the plain one)

    # --- feed ---
    def latest(self):
        return RobotView(dict(self.angles), self.rear, 0.0, 0.0, 1.0, dict(self.efforts))

    def check(self):
        """Never cancelled, never stale."""

    # --- primitives ---
    def change_control_mode(self, joint, mode):
        """Modes do not matter to kinematics."""

    def drive_at_velocity(self, mm_s):
        """Wheels: the kinematic robot does not travel."""
        self.wheels = mm_s

    def move_module(self, joint, counts):
        """A bend's torque setpoint: 0 releases its spring."""
        if counts == 0:
            self.efforts[joint] = 0.0

    def hold(self, *joints):
        """Worm-held at PWM 0: kinematically, the springs let go (as a 0 setpoint)."""
        for joint in joints:
            self.move_module(joint, 0)

    def move_front(self, kind='move_front'):
        self.executed.append(report_kind(kind).replace('_', ' '))
        self.angles['front_tilt'] = self.guards.move(kind).guard

    def clamp(self, part, kind='clamp'):
        self.executed.append(clamp_name(kind, part))
        pair = self.guards.pair(kind, part)
        if (part == 'front' and self.front_wall_on_side is not None and clamp_state.on_side(self.guards, self.front)
                and pair.outer.guard < self.front_wall_on_side):
            raise TimedOut('%s: the V meets the walls at %.3f rad on a side, short of %.3f'
                           % (clamp_name(kind, part), self.front_wall_on_side, pair.outer.guard))
        self.angles.update({pair.outer.joint: pair.outer.guard - 0.01, pair.inner.joint: pair.inner.guard + 0.01})
        self.efforts[pair.outer.joint] = PRESS_MNM
        self.clamped[part] = True

    def unclamp(self, part, partial=False, row=None):
        self.executed.append('unclamp %s%s' % (part, ' partial' if partial else ''))
        self.unclamp_rows.append(row)
        pair = self.guards.pair(row or ('unclamp_partial' if partial else 'unclamp'), part)
        self.angles.update({pair.outer.joint: pair.outer.guard + 0.01, pair.inner.joint: pair.inner.guard - 0.01})
        self.efforts[pair.outer.joint] = 0.0
        self.clamped[part] = False

    def rotate(self, target_rad, name='rotate'):
        if not safety.rotation_ok(target_rad):
            raise Refused('rotation %.3f beyond the limit' % target_rad)
        assert not all(self.clamped.values()), 'rotating against two clamped parts'
        self.executed.append(name)
        self.rotation = self.angles['rotation'] = target_rad
        if self.clamped['front']:
            self.rear = self.front + target_rad
        else:
            self.front = self.rear - target_rad     # rear clamped, or the lighter front

    def align(self):
        self.rotate(0.0, name='align')


def run(pab, robot, goal=None):
    ctx = PabContext(robot, robot, robot.guards, goal, lambda *state: None)
    return pab.run(ctx)
