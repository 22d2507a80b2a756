"""Every launch file parses and names only nodes that exist (roslaunch-check).

The spirit of roslaunch_add_file_check: a broken include, arg or node type
fails here, not on the robot.
"""
import glob
import os
import subprocess

import pytest
from roslaunch import rlutil

LAUNCH_DIR = os.path.join(os.path.dirname(__file__), '..', '..', 'launch')
LAUNCH_FILES = sorted(glob.glob(os.path.join(LAUNCH_DIR, '*.launch')))


def test_there_are_launch_files():
    assert len(LAUNCH_FILES) >= 10


@pytest.mark.parametrize('path', LAUNCH_FILES, ids=os.path.basename)
def test_launch_file_is_valid(path):
    assert rlutil.check_roslaunch(path) is None


@pytest.mark.parametrize('robot', ['sim', 'fil', 'real'])
def test_robot_argument_selects_a_robot_end(robot):
    nodes = subprocess.run(['roslaunch', '--nodes', os.path.join(LAUNCH_DIR, 'Manager.launch'),
                            'robot:=%s' % robot, 'panel:=none'],
                           capture_output=True, text=True, timeout=60)
    assert nodes.returncode == 0, nodes.stderr
    assert '/pirate_manager' in nodes.stdout and '/pirate_state' in nodes.stdout
    expected = {'sim': '/sim_robot', 'fil': '/fil_robot', 'real': '/serial_node'}[robot]
    assert expected in nodes.stdout
