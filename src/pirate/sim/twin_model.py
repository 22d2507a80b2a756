"""The whole MuJoCo model (MJCF text) of PIRATE in a pipe network.

Assembles the walls (pirate.sim.twin_pipes) and the robot
(pirate.sim.twin_robot) with the actuators the boards drive
(pirate.sim.boards): each bend a position servo whose stiffness is the
series spring (report 2.4.3.1) and whose target is the worm's angle; front
tilt and cameras stiff servos on their gear output; the rotation a servo
with the motor's torque limit, its damping on the joint (twin_robot); each wheel a velocity servo with the wheel
motor's torque limit. Gravity acts on every body. Pure: writes XML.
"""
import os
import xml.etree.ElementTree as ET

import yaml

from pirate import paths
from pirate.robot import tables
from pirate.sim import twin_pipes, twin_robot

CONFIG_FILE = os.path.join(paths.CONFIG_DIR, 'twin.yaml')
GEAR_SERVO_NM_PER_RAD = 20.0     # stiff: the gear output does not give
BEND_JOINTS = tables.BEND_JOINTS
GEAR_JOINTS = ('front_tilt', 'camera_tilt', 'camera_pan')
ROOM_LIGHT = 'room_light'


def load_config(path=CONFIG_FILE):
    """The twin's constants (config/twin.yaml)."""
    with open(path) as stream:
        return yaml.safe_load(stream)


def bore_error_m(world, config):
    """The twin's bore minus the world's diameter, m: the world's pipe (its
    wall, ``pipe:``) and the twin's ``pipe.bore_error_mm`` (a tolerance)."""
    return world.bore_offset_m + config['pipe']['bore_error_mm'] / 1000.0


def bore_at(world, config, along_m):
    """The twin's bore (m) at ``along_m``: where its walls stand."""
    return world.diameter_at(along_m) + bore_error_m(world, config)


def start_pose(world, config, roll):
    """Root position and axes: the robot's middle at the world's start,
    its wheels just above the pipe floor, rolled by ``roll`` (Fig 4.7)."""
    _, frame = world.locate(world.start_m)
    radius = bore_at(world, config, world.start_m) / 2
    clearance = config['geometry']['wheel_diameter_m'] / 2 + 0.003
    pos = tuple(o - z * (radius - clearance) for o, z in zip(frame.origin, frame.axes[2]))
    return pos, twin_robot.roll_axes(roll)


def _defaults(root, config):
    default = ET.SubElement(root, 'default')
    physics = config['physics']
    ET.SubElement(default, 'joint', damping='%g' % physics['joint_damping_nms'], armature='1e-5')
    for name, friction, contype, conaffinity, rgba in (
            (twin_pipes.PIPE_CLASS, config['friction']['body'], 0, 1, '0.6 0.7 0.8 0.35'),
            (twin_robot.ROBOT_CLASS, config['friction']['body'], 1, 0, '0.85 0.55 0.2 1'),
            (twin_robot.WHEEL_CLASS, config['friction']['wheel'], 1, 0, '0.1 0.1 0.1 1')):
        cls = ET.SubElement(default, 'default', {'class': name})
        ET.SubElement(cls, 'geom', friction='%g 0.005 0.0001' % friction, contype=str(contype),
                      conaffinity=str(conaffinity), rgba=rgba, condim='4' if name != twin_pipes.PIPE_CLASS else '3',
                      group=str(twin_pipes.PIPE_GROUP if name == twin_pipes.PIPE_CLASS else 0))


def actuator_names():
    """Every actuator :func:`model_xml` writes, by name."""
    return BEND_JOINTS + GEAR_JOINTS + ('rotation',) + tuple(twin_robot.wheel_joint(b) for b in tables.DRIVE_BOARDS)


def _actuators(root, config):
    act = ET.SubElement(root, 'actuator')
    bend = config['bend']
    for joint in BEND_JOINTS:
        ET.SubElement(act, 'position', name=joint, joint=joint, kp='%g' % bend['spring_nm_per_rad'])
    for joint in GEAR_JOINTS:
        ET.SubElement(act, 'position', name=joint, joint=joint, kp='%g' % GEAR_SERVO_NM_PER_RAD,
                      kv='0.05')
    rot = config['rotation']
    ET.SubElement(act, 'position', name='rotation', joint='rotation', kp='%g' % rot['kp_nm_per_rad'],
                  forcelimited='true', forcerange='%g %g' % (-rot['max_nm'], rot['max_nm']))
    wheel = config['wheel']
    for board in tables.DRIVE_BOARDS:
        ET.SubElement(act, 'velocity', name=twin_robot.wheel_joint(board), joint=twin_robot.wheel_joint(board),
                      kv='%g' % wheel['kv_nms_per_rad'], forcelimited='true',
                      forcerange='%g %g' % (-wheel['stall_nm'], wheel['stall_nm']))


def model_xml(world, config, roll):
    """MJCF text of ``world`` (a pirate.world.network.Network) with the robot."""
    root = ET.Element('mujoco', model='pirate_' + str(world.name))
    ET.SubElement(root, 'compiler', angle='radian')
    option = ET.SubElement(root, 'option', timestep='%g' % config['physics']['timestep_s'], gravity='0 0 -9.81',
                           integrator='implicitfast', cone='elliptic',
                           impratio='%g' % config['physics']['friction_impratio'],
                           jacobian=config['physics']['jacobian'],
                           ccd_iterations='%d' % config['physics']['ccd_iterations'])
    # Nothing newer than MuJoCo 3.2.3, the newest with Python 3.8 wheels; measurements.md#twin-sleeping
    ET.SubElement(option, 'flag', multiccd='enable' if config['physics']['multiccd'] else 'disable',
                  nativeccd='enable' if config['physics']['native_ccd'] else 'disable')
    ET.SubElement(root, 'visual').append(ET.Element('global', offwidth='640', offheight='480'))
    _defaults(root, config)
    body = ET.SubElement(root, 'worldbody')
    ET.SubElement(body, 'light', name=ROOM_LIGHT, pos='0 0 2', dir='0 0 -1')   # viewers only; cameras see by the LEDs
    walls = twin_pipes.WallBuilder(body, config['physics']['wall_segments'], config['physics']['wall_thickness_m'],
                                   bore_error_m(world, config))
    walls.network(world)
    pos, axes = start_pose(world, config, roll)
    twin_robot.RobotBuilder(config).build(body, pos, axes)
    _actuators(root, config)
    ET.SubElement(root, 'sensor').append(ET.Element('framequat', name='imu_quat', objtype='site', objname='imu'))
    return ET.tostring(root, encoding='unicode')
