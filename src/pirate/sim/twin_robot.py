"""PIRATE as a MuJoCo body tree, generated from the module table.

Seven modules front to rear (report Fig 2.7; pirate.robot.tables): Front,
Bend I, Bend II, Rotational (two halves turning about the robot's axis),
Bend III, Bend IV, Rear. Each module is ``module_length_m`` (report l)
between its joint axes. A pitch joint sits between neighbours and carries a
driven wheel of diameter D_w on its axis (so a clamp's V has the report's
geometry, eq 2.1: sin(e) = (D_p - D_w) / l):

====================  ===========  =====================================
joint (tables.JOINTS)  between     wheel of board (tables.DRIVE_BOARDS)
====================  ===========  =====================================
front_tilt            Front/I      22 (Bend I)
bend_i                I/II         23 (Bend II)   apex of the front V
bend_ii               II/Rot       24 (Rotational)
bend_iii              Rot/III      25 (Rotational)
bend_iv               III/IV       26 (Bend III)  apex of the rear V
rear_tilt             IV/Rear      27 (Bend IV)
====================  ===========  =====================================

The apex wheels touch the ceiling, so they turn the other way to drive the
same way: that is the per-board sign of tables.WHEEL_SIGN. Angles: a
positive bend lifts the far end of the module further from the middle
(inner bends +e, outer -2e in a clamp, SPEC 7). Robot frame: x forward,
y left, z up when upright (roll pi/2, Fig 4.7); the root is the rear half
of the rotational module, carrying the IMU (board 25, Table B.1).
Pure: writes MJCF elements; masses and sizes are in config/twin.yaml,
their sources in config/twin_sources.yaml.
"""
import math
import xml.etree.ElementTree as ET

from pirate.robot import tables

#: (module, joint that attaches it to the previous one, the wheel's board at
#: that joint) from the middle outwards, for the front side and the rear.
FRONT_CHAIN = (('bend_ii_module', 'bend_ii', 24), ('bend_i_module', 'bend_i', 23),
               ('front_module', 'front_tilt', 22))
REAR_CHAIN = (('bend_iii_module', 'bend_iii', 25), ('bend_iv_module', 'bend_iv', 26),
              ('rear_module', 'rear_tilt', 27))
ROBOT_CLASS = 'robot'
WHEEL_CLASS = 'wheel'
ROOT = 'rotational_rear'
ROOT_JOINT = 'root'
ROTATIONAL_FRONT = 'rotational_front'
#: Bodies whose true pose the ground truth reports, front to rear
#: (names.GROUND_TRUTH_TOPIC's poses, in this order).
TRUTH_BODIES = tuple(m for m, _, _ in reversed(FRONT_CHAIN)) + (ROTATIONAL_FRONT, ROOT) + tuple(
    m for m, _, _ in REAR_CHAIN)
CAMERA_BODIES = (('camera_tilt', (0, -1, 0)), ('camera_pan', (0, 0, 1)))
#: MuJoCo cameras and the LED lights beside them: the front camera on the
#: pan/tilt, the rear camera fixed in the rear module's end, each looking
#: out along the robot's axis (a MuJoCo camera looks along its -z, image up
#: along its y: the robot's z).
FRONT_CAMERA, REAR_CAMERA = 'front_camera', 'rear_camera'
FRONT_LED, REAR_LED = 'front_led', 'rear_led'
LOOKING = {1: '0 -1 0 0 0 1', -1: '0 1 0 0 0 1'}     # xyaxes looking forward (+1) / backward (-1)


def _fmt(values):
    return ' '.join('%.6g' % v for v in values)


def _cylinder_inertia(mass, radius, length):
    """Diagonal inertia of a uniform cylinder along x (a module's shell, a wheel's disc)."""
    across = mass * (3 * radius * radius + length * length) / 12
    return (mass * radius * radius / 2, across, across)


def wheel_joint(board):
    """Name of the wheel joint of drive ``board``."""
    return 'wheel_%d' % board


def chain_joints():
    """Every joint the generated tree has, for checks against tables."""
    pitch = [joint for _, joint, _ in FRONT_CHAIN + REAR_CHAIN]
    return pitch + ['rotation', 'camera_tilt', 'camera_pan'] + [wheel_joint(b) for b in tables.DRIVE_BOARDS]


class RobotBuilder(object):
    """Adds the robot's body tree under ``parent`` (the worldbody)."""

    def __init__(self, config):
        self.geo, self.mass = config['geometry'], config['masses_kg']
        self.cfg = config

    def _module(self, body, name, mass, direction, length):
        """A module's inertial and round collision shell about its axis, reaching ``length`` from
        the body origin in ``direction`` (+1 front, -1 rear).

        The front module's shell is a capsule of the same length: it has no
        wheel and rides on the floor ahead of the front V, and a flat
        cylinder end caught the edge where two wall pieces meet (a mitre
        bend's inner corner, a T-joint's run) and stopped the robot there."""
        radius = self.geo['body_radius_m']
        centre = (direction * length / 2, 0, 0)
        ET.SubElement(body, 'inertial', pos=_fmt(centre), mass='%g' % mass,
                      diaginertia=_fmt(_cylinder_inertia(mass, radius, length)))
        end = name == 'front_module'
        ET.SubElement(body, 'geom', type='capsule' if end else 'cylinder', pos=_fmt(centre),
                      size=_fmt((radius, length / 2 - (radius if end else 0.0))),
                      euler='0 1.5708 0', name=name + '_shell', **{'class': ROBOT_CLASS})

    def _wheel(self, body, board, x):
        radius = self.geo['wheel_diameter_m'] / 2
        wheel = ET.SubElement(body, 'body', name='wheel_body_%d' % board, pos=_fmt((x, 0, 0)))
        mass = self.mass['wheel']
        axial, across, _ = _cylinder_inertia(mass, radius, 2 * self.geo['wheel_half_width_m'])
        ET.SubElement(wheel, 'inertial', pos='0 0 0', mass='%g' % mass, diaginertia=_fmt((across, axial, across)))
        ET.SubElement(wheel, 'joint', name=wheel_joint(board), type='hinge', axis='0 1 0')
        ET.SubElement(wheel, 'geom', type='cylinder', size=_fmt((radius, self.geo['wheel_half_width_m'])),
                      euler='1.5708 0 0', name='wheel_geom_%d' % board, **{'class': WHEEL_CLASS})

    def _chain(self, parent, chain, direction):
        length = self.geo['module_length_m']
        x = direction * length / 2          # the rotational half's far end
        axis = (0, -direction, 0)           # positive lifts the far end
        for module, joint, board in chain:
            body = ET.SubElement(parent, 'body', name=module, pos=_fmt((x, 0, 0)))
            limit = self.cfg['bend']['joint_range_rad']
            ET.SubElement(body, 'joint', name=joint, type='hinge', axis=_fmt(axis),
                          range=_fmt((-limit, limit)), limited='true')
            self._wheel(body, board, 0.0)
            end = module in ('front_module', 'rear_module')
            mass = self.mass['front' if module == 'front_module' else 'rear' if end else 'bend']
            self._module(body, module, mass, direction,
                         self.geo['front_length_m'] if module == 'front_module' else length)
            if module == 'front_module':
                self._cameras(body)
                self._led(body, FRONT_LED, self.geo['front_length_m'], 1)
            if module == 'rear_module':
                ET.SubElement(body, 'camera', name=REAR_CAMERA, pos=_fmt((-length, 0, 0)), xyaxes=LOOKING[-1],
                              fovy='%g' % self.cfg['cameras']['fovy_deg'])
                self._led(body, REAR_LED, length, -1)
            parent, x = body, direction * length

    def _cameras(self, front):
        """Camera tilt and pan: light bodies in the front dome."""
        parent = front
        for name, axis in CAMERA_BODIES:
            body = ET.SubElement(parent, 'body', name=name + '_body', pos=_fmt((self.geo['front_length_m'] * 0.8, 0, 0)
                                                                          if parent is front else (0, 0, 0)))
            ET.SubElement(body, 'inertial', pos='0 0 0', mass='0.01', diaginertia='1e-6 1e-6 1e-6')
            limit = self.cfg['camera']['range_rad']
            ET.SubElement(body, 'joint', name=name, type='hinge', axis=_fmt(axis), range=_fmt(limit), limited='true')
            parent = body
        ET.SubElement(parent, 'camera', name=FRONT_CAMERA, pos='0 0 0', xyaxes=LOOKING[1],
                      fovy='%g' % self.cfg['cameras']['fovy_deg'])

    def _led(self, body, name, x, direction):
        """The LEDs at a module's end, one spot light along the axis (off
        until the board lights them: pirate.sim.twin_camera)."""
        cams = self.cfg['cameras']
        ET.SubElement(body, 'light', name=name, pos=_fmt((direction * x, 0, 0)), dir=_fmt((direction, 0, 0)),
                      cutoff='%g' % cams['led_cutoff_deg'], exponent='2', attenuation=_fmt(cams['led_attenuation']),
                      castshadow='false', diffuse='0 0 0', specular='0 0 0', ambient='0 0 0')

    def build(self, parent, pos, xyaxes):
        """The robot with its root (rotational rear half) at ``pos``."""
        half = self.geo['module_length_m'] / 2
        root = ET.SubElement(parent, 'body', name=ROOT, pos=_fmt(pos), xyaxes=_fmt(xyaxes))
        ET.SubElement(root, 'freejoint', name=ROOT_JOINT)
        self._module(root, ROOT, self.mass['rotational_half'], -1, half)
        ET.SubElement(root, 'site', name='imu', pos='0 0 0')
        front = ET.SubElement(root, 'body', name=ROTATIONAL_FRONT, pos='0 0 0')
        rot = self.cfg['rotation']   # the motor's damping is not clipped by its torque limit (config/twin.yaml)
        ET.SubElement(front, 'joint', name='rotation', type='hinge', axis='1 0 0',
                      damping='%g' % (self.cfg['physics']['joint_damping_nms'] + rot['kv_nms_per_rad']))
        self._module(front, ROTATIONAL_FRONT, self.mass['rotational_half'], 1, half)
        self._chain(front, FRONT_CHAIN, 1)
        self._chain(root, REAR_CHAIN, -1)
        return root


def roll_axes(roll):
    """Robot x/y axes (world) for a roll about the world x axis (Fig 4.7):
    the robot's up (z) is world up at pi/2; at 0 its left (y) points up."""
    alpha = math.pi / 2 - roll
    return (1, 0, 0, 0, math.cos(alpha), math.sin(alpha))
