"""Build PIRATE's URDF from a module table (no xacro on this machine).

The checked-in ``urdf/pirate.urdf`` is this module's output; a unit test
regenerates it and compares, so edit the table here and rerun::

    python3 -m pirate.viz.urdf_gen urdf/pirate.urdf

Kinematics (SPEC 2, report Fig 2.7). Seven modules front to rear: Front,
Bend I, Bend II, Rotational, Bend III, Bend IV, Rear, each 0.09 m long. The
base link is the rear half of the rotational module: it carries the IMU
(board 25, Table B.1), and the IMU measures the rear part's roll, so the
roll the viz node applies to the base frame is exactly what was measured.
From there one chain runs forward (rotation, bend_ii, bend_i, front_tilt,
camera_tilt, camera_pan) and one backward (bend_iii, bend_iv, rear_tilt).

Frames follow REP 103 with the robot upright (orientation pi/2, Fig 4.7):
x forward along the pipe, y to the robot's left, z up. The bends pitch the
modules in the x-z plane. Each joint sits between two modules:

=========== ========================== =====================================
joint       between                    positive angle
=========== ========================== =====================================
front_tilt  Bend I -> Front            lifts the front module (move front)
bend_i      Bend II -> Bend I          lifts Bend I's far end
bend_ii     Rotational -> Bend II      lifts Bend II's far end
rotation    rotational rear -> front   front part rolls by +theta about x
bend_iii    Rotational -> Bend III     lifts Bend III's far end
bend_iv     Bend III -> Bend IV        lifts Bend IV's far end
rear_tilt   Bend IV -> Rear            lifts the rear module
=========== ========================== =====================================

So a clamp (Table 5.2: outer Bend I/IV negative, inner Bend II/III
positive) draws a V with its apex at bend_i (bend_iv) towards +z and the
rotational module's wheels on the -z wall. The rotation sign follows the
simulator and eq 5.1: theta = rear roll - front roll in the orientation of
Fig 4.7, whose roll runs opposite to REP 103's (see pirate.viz.pose).

Each module carries one wheel (diameter 0.046 m) on a fixed joint, so the
only moving joints are tables.JOINT_NAMES, which the state node publishes.
"""
import math
import sys
import xml.etree.ElementTree as ET

from pirate import names
from pirate.robot import safety

MODULE_LENGTH = 0.09      # m, l in eq 2.1 (report 2.4.1.1)
WHEEL_DIAMETER = 0.046    # m, D_omega (report 2.4.1.1)
WHEEL_WIDTH = 0.04        # m, drawing only (wider than the body, so seen from above)
BODY_WIDTH = 0.034        # m, module box across y and z (drawing only;
                          # narrower than the wheel so the wheels show)
BODY_GAP = 0.012          # m, left between module boxes so the joints show

#: Colours, RGBA. Distinct hues so a screenshot test can find the robot.
MATERIALS = (
    ('pirate_orange', (1.0, 0.45, 0.0, 1.0)),
    ('wheel_dark', (0.12, 0.12, 0.12, 1.0)),
    ('camera_blue', (0.1, 0.3, 0.9, 1.0)),
)

# Directions along the robot: the front chain grows along +x, the rear -x.
FORWARD, BACKWARD = 1, -1

#: The module table, front to rear: (module, link, length m, wheel link or
#: None, direction). The rotational module is split at its rotation joint
#: into two links of half a module; each of its two PICO boards drives one
#: wheel (Table 2.1), so six wheels in all, on the drive boards 22..27.
MODULES = (
    ('Front', 'front_module', MODULE_LENGTH, None, FORWARD),
    ('Bend I', 'bend_i_module', MODULE_LENGTH, 'bend_i_wheel', FORWARD),
    ('Bend II', 'bend_ii_module', MODULE_LENGTH, 'bend_ii_wheel', FORWARD),
    ('Rotational, front half (board 24)', 'rotational_front', MODULE_LENGTH / 2,
     'rotational_front_wheel', FORWARD),
    ('Rotational, rear half (board 25, IMU)', 'base_link', MODULE_LENGTH / 2,
     'rotational_rear_wheel', BACKWARD),
    ('Bend III', 'bend_iii_module', MODULE_LENGTH, 'bend_iii_wheel', BACKWARD),
    ('Bend IV', 'bend_iv_module', MODULE_LENGTH, 'bend_iv_wheel', BACKWARD),
    ('Rear', 'rear_module', MODULE_LENGTH, None, BACKWARD),
)
BASE_LINK = 'base_link'

# Half a turn of the AS5055 either way: the most any encoder joint can read.
ENCODER_LIMIT = math.pi

#: Moving joints: (name, parent, child, axis, lower, upper). A joint sits at
#: the parent module's far end, except the rotation, which is the base
#: link's origin (the middle of the rotational module). The pitch axis is -y on the front
#: chain and +y on the rear chain, so a positive angle lifts the far end of
#: the child on both (the mirrored modules of SPEC 3, drawn the same way).
JOINTS = (
    ('rotation', BASE_LINK, 'rotational_front', (1, 0, 0),
     -safety.ROTATION_MAX_RAD, safety.ROTATION_MAX_RAD),
    ('bend_ii', 'rotational_front', 'bend_ii_module', (0, -1, 0), -ENCODER_LIMIT, ENCODER_LIMIT),
    ('bend_i', 'bend_ii_module', 'bend_i_module', (0, -1, 0), -ENCODER_LIMIT, ENCODER_LIMIT),
    ('front_tilt', 'bend_i_module', 'front_module', (0, -1, 0), -ENCODER_LIMIT, ENCODER_LIMIT),
    ('camera_tilt', 'front_module', 'camera_tilt_link', (0, -1, 0), -ENCODER_LIMIT, ENCODER_LIMIT),
    ('camera_pan', 'camera_tilt_link', 'camera_link', (0, 0, 1), -ENCODER_LIMIT, ENCODER_LIMIT),
    ('bend_iii', BASE_LINK, 'bend_iii_module', (0, 1, 0), -ENCODER_LIMIT, ENCODER_LIMIT),
    ('bend_iv', 'bend_iii_module', 'bend_iv_module', (0, 1, 0), -ENCODER_LIMIT, ENCODER_LIMIT),
    ('rear_tilt', 'bend_iv_module', 'rear_module', (0, 1, 0), -ENCODER_LIMIT, ENCODER_LIMIT),
)

CAMERA_SIZE = 0.02   # m, cube drawn for the camera head
#: A camera's optical frame (REP 103: z out of the lens, x right, y down)
#: turned from a link whose x looks out of the lens.
OPTICAL_RPY = (-math.pi / 2, 0, -math.pi / 2)


def _fmt(values):
    """Space-separated numbers, rounded so the text is stable across runs."""
    return ' '.join(('%.6g' % (0.0 if abs(v) < 1e-12 else v)) for v in values)


def _module(link):
    """(length m, wheel link, direction) of a module link, None if no module."""
    for _, name, length, wheel, direction in MODULES:
        if name == link:
            return length, wheel, direction
    return None


def _visual(parent, xyz, rpy, geometry, material):
    visual = ET.SubElement(parent, 'visual')
    ET.SubElement(visual, 'origin', xyz=_fmt(xyz), rpy=_fmt(rpy))
    shape = ET.SubElement(ET.SubElement(visual, 'geometry'), geometry[0])
    for key, value in geometry[1].items():
        shape.set(key, _fmt(value) if isinstance(value, tuple) else _fmt((value,)))
    ET.SubElement(visual, 'material', name=material)


def _module_link(robot, link):
    """A module: an orange box from its joint to its far end, plus a wheel."""
    length, wheel, direction = _module(link)
    element = ET.SubElement(robot, 'link', name=link)
    centre = (direction * length / 2, 0, 0)
    _visual(element, centre, (0, 0, 0),
            ('box', {'size': (length - BODY_GAP, BODY_WIDTH, BODY_WIDTH)}), 'pirate_orange')
    if wheel:
        # A cylinder's axis is its z; roll it onto y, the wheel's axle.
        _visual(ET.SubElement(robot, 'link', name=wheel), (0, 0, 0), (math.pi / 2, 0, 0),
                ('cylinder', {'radius': WHEEL_DIAMETER / 2, 'length': WHEEL_WIDTH}), 'wheel_dark')
        _fixed(robot, wheel + '_joint', link, wheel, centre)


def _fixed(robot, name, parent, child, xyz, rpy=(0, 0, 0)):
    joint = ET.SubElement(robot, 'joint', name=name, type='fixed')
    ET.SubElement(joint, 'parent', link=parent)
    ET.SubElement(joint, 'child', link=child)
    ET.SubElement(joint, 'origin', xyz=_fmt(xyz), rpy=_fmt(rpy))


def _camera_frames(robot):
    """The frames the camera images are stamped in: the front camera's on
    the pan/tilt head, the rear camera's at the rear module's end looking back."""
    for camera in ('front', 'rear'):
        ET.SubElement(robot, 'link', name=names.CAMERA_FRAMES[camera])
    _fixed(robot, 'front_camera_optical_joint', 'camera_link', names.CAMERA_FRAMES['front'],
           (CAMERA_SIZE, 0, 0), OPTICAL_RPY)
    ET.SubElement(robot, 'link', name='rear_camera_link')
    _fixed(robot, 'rear_camera_joint', 'rear_module', 'rear_camera_link', (-MODULE_LENGTH, 0, 0), (0, 0, math.pi))
    _fixed(robot, 'rear_camera_optical_joint', 'rear_camera_link', names.CAMERA_FRAMES['rear'], (0, 0, 0),
           OPTICAL_RPY)


def _joint_origin(name, parent):
    """Where joint ``name`` sits in its parent's frame (see JOINTS)."""
    module = _module(parent)
    if name == 'rotation' or module is None:   # camera pan: on the tilt axis
        return (0, 0, 0)
    length, _, direction = module
    return (direction * length, 0, 0)


def build():
    """The URDF as an ElementTree root element."""
    robot = ET.Element('robot', name='pirate')
    robot.append(ET.Comment(' Generated by pirate.viz.urdf_gen; do not edit by hand. '))
    for name, rgba in MATERIALS:
        ET.SubElement(ET.SubElement(robot, 'material', name=name), 'color', rgba=_fmt(rgba))
    for _, link, _, _, _ in MODULES:
        _module_link(robot, link)
    ET.SubElement(robot, 'link', name='camera_tilt_link')
    camera = ET.SubElement(robot, 'link', name='camera_link')
    _visual(camera, (CAMERA_SIZE / 2, 0, 0), (0, 0, 0),
            ('box', {'size': (CAMERA_SIZE,) * 3}), 'camera_blue')
    ET.SubElement(robot, 'link', name='imu_link')
    _fixed(robot, 'imu_joint', BASE_LINK, 'imu_link', (-MODULE_LENGTH / 4, 0, 0))
    _camera_frames(robot)
    for name, parent, child, axis, lower, upper in JOINTS:
        joint = ET.SubElement(robot, 'joint', name=name, type='revolute')
        ET.SubElement(joint, 'parent', link=parent)
        ET.SubElement(joint, 'child', link=child)
        ET.SubElement(joint, 'origin', xyz=_fmt(_joint_origin(name, parent)),
                      rpy=_fmt((0, 0, 0)))
        ET.SubElement(joint, 'axis', xyz=_fmt(axis))
        # effort and velocity are required by the URDF schema; nothing in
        # this stack reads them (robot_state_publisher and RViz do not).
        ET.SubElement(joint, 'limit', lower=_fmt((lower,)), upper=_fmt((upper,)),
                      effort='0', velocity='0')
    return robot


def _indent(element, level=0, space='  '):
    """Indent ``element``'s children in place, as ElementTree.indent
    (Python 3.9 on) does."""
    if len(element) == 0:
        return
    inner = '\n' + space * (level + 1)
    if not (element.text or '').strip():
        element.text = inner
    for child in element:
        _indent(child, level + 1, space)
        if not (child.tail or '').strip():
            child.tail = inner
    if not (element[-1].tail or '').strip():
        element[-1].tail = '\n' + space * level


def generate():
    """The URDF text, deterministic (the checked-in file must equal it)."""
    root = build()
    _indent(root)
    return '<?xml version="1.0"?>\n' + ET.tostring(root, encoding='unicode') + '\n'


def moving_joints(urdf_text):
    """Names of the non-fixed joints in a URDF text."""
    root = ET.fromstring(urdf_text)
    return {j.get('name') for j in root.iter('joint') if j.get('type') != 'fixed'}


def main(argv=None):
    """Write the URDF to the path given (or stdout)."""
    argv = sys.argv[1:] if argv is None else argv
    text = generate()
    if argv:
        with open(argv[0], 'w') as out:
            out.write(text)
    else:
        sys.stdout.write(text)


if __name__ == '__main__':
    main()
