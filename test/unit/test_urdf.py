"""The URDF: generated from the module table, valid, and joint-for-joint
the joints the Pirate State node publishes (tables.JOINT_NAMES)."""
import math
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

from pirate import names
from pirate.robot import tables
from pirate.viz import pose, urdf_gen

URDF = os.path.join(os.path.dirname(__file__), '..', '..', 'urdf', 'pirate.urdf')


def _text():
    with open(URDF) as f:
        return f.read()


def test_checked_in_urdf_is_the_generators_output():
    assert _text() == urdf_gen.generate(), (
        'urdf/pirate.urdf is stale: run python3 -m pirate.viz.urdf_gen urdf/pirate.urdf')


def test_moving_joints_are_exactly_the_published_joints():
    assert urdf_gen.moving_joints(_text()) == set(tables.JOINT_NAMES)


@pytest.mark.skipif(shutil.which('check_urdf') is None,
                    reason='check_urdf missing (Debian package liburdfdom-tools)')
def test_check_urdf_passes():
    out = subprocess.run(['check_urdf', URDF], capture_output=True, text=True, timeout=30)
    assert out.returncode == 0, out.stdout + out.stderr
    assert 'root Link: base_link' in out.stdout


def test_seven_modules_and_six_wheels():
    root = ET.fromstring(_text())
    links = {l.get('name') for l in root.iter('link')}
    assert {m[1] for m in urdf_gen.MODULES} <= links
    wheels = [l for l in root.iter('link') if l.get('name').endswith('_wheel')]
    assert len(wheels) == 6
    for wheel in wheels:
        cylinder = wheel.find('visual/geometry/cylinder')
        assert float(cylinder.get('radius')) * 2 == pytest.approx(0.046)
    # Front to rear: 3 + 2 halves + 3 modules of 0.09 m make 0.63 m.
    assert sum(m[2] for m in urdf_gen.MODULES) == pytest.approx(7 * 0.09)


def test_every_visual_has_a_defined_material():
    root = ET.fromstring(_text())
    defined = {m.get('name') for m in root.findall('material')}
    used = {m.get('name') for m in root.iter('material') if m.find('color') is None}
    assert used and used <= defined


def _chain_to(root, link):
    """Joints from the base link down to ``link``."""
    parent_of = {j.find('child').get('link'): j for j in root.iter('joint')}
    chain = []
    while link in parent_of:
        chain.append(parent_of[link])
        link = parent_of[link].find('parent').get('link')
    return list(reversed(chain)), link


def _apex_height(angles):
    """z of the bend_i joint above the base for the front V (planar)."""
    root = ET.fromstring(_text())
    chain, base = _chain_to(root, 'bend_i_module')
    assert base == urdf_gen.BASE_LINK
    x = z = pitch = 0.0
    for joint in chain:
        ox = float(joint.find('origin').get('xyz').split()[0])
        x, z = x + ox * math.cos(pitch), z + ox * math.sin(pitch)
        axis_y = float(joint.find('axis').get('xyz').split()[1])
        # Rotation about -y by +a lifts +x: pitch up by a.
        pitch += -axis_y * angles.get(joint.get('name'), 0.0)
    return z


def test_clamp_front_lifts_the_apex():
    """Table 5.2 clamp front: Bend I -0.77, Bend II +0.35 makes a V whose
    apex (the bend_i joint) rises off the rotational module's wall."""
    assert _apex_height({}) == pytest.approx(0.0)
    assert _apex_height({'bend_i': -0.77, 'bend_ii': 0.35}) > 0.02


def test_base_pose_follows_fig_4_7():
    upright, q_up = pose.base_in_pipe(math.pi / 2, 90)
    assert q_up == pytest.approx((0, 0, 0, 1))
    # (90 - 46) / 2 mm below the axis: the rear wheels on the bottom wall.
    assert upright == pytest.approx((0, 0, -0.022))
    right, q_right = pose.base_in_pipe(0.0, 90)
    # Lying on its right side, a roll of +pi/2 about x: the robot's top
    # (+z) turns to the pipe's right, its belly (-z, the rear wheels' wall)
    # to the pipe's left (+y), its left side (+y) up.
    assert right == pytest.approx((0, 0.022, 0), abs=1e-12)
    assert q_right == pytest.approx((math.sin(math.pi / 4), 0, 0, math.cos(math.pi / 4)))


@pytest.mark.parametrize('orientation, diameter', [
    (float('nan'), 90), (float('inf'), 90), (1.57, 40), (1.57, 0)])
def test_bad_pose_inputs_are_refused(orientation, diameter):
    with pytest.raises(ValueError):
        pose.base_in_pipe(orientation, diameter)


@pytest.mark.parametrize('camera, parent', [('front', 'camera_link'), ('rear', 'rear_camera_link')])
def test_camera_images_have_optical_frames_looking_out_of_the_lens(camera, parent):
    root = ET.fromstring(_text())
    frame = names.CAMERA_FRAMES[camera]
    joint = next(j for j in root.iter('joint') if j.find('child').get('link') == frame)
    assert joint.get('type') == 'fixed' and joint.find('parent').get('link') == parent
    roll, pitch, yaw = (float(v) for v in joint.find('origin').get('rpy').split())
    # the optical z (out of the lens) in the parent's frame: rpy (-pi/2, 0, -pi/2) turns it onto x
    z = (math.cos(yaw) * math.sin(pitch) * math.cos(roll) + math.sin(yaw) * math.sin(roll),
         math.sin(yaw) * math.sin(pitch) * math.cos(roll) - math.cos(yaw) * math.sin(roll),
         math.cos(pitch) * math.cos(roll))
    assert z == pytest.approx((1, 0, 0), abs=1e-4)      # the URDF keeps 6 digits
    if camera == 'rear':      # the rear camera link looks back along the rear module
        turn = next(j for j in root.iter('joint') if j.find('child').get('link') == parent)
        assert turn.find('parent').get('link') == 'rear_module'
        assert float(turn.find('origin').get('rpy').split()[2]) == pytest.approx(math.pi, abs=1e-4)
