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


# --- every argument documented, values checked -----------------------------

def _user_args(path):
    """(name, attributes) of every <arg> a user can set (those with a default)."""
    import xml.etree.ElementTree as ET
    return [(a.get('name'), a.attrib) for a in ET.parse(path).getroot().iter('arg')
            if 'value' not in a.attrib]


@pytest.mark.parametrize('path', LAUNCH_FILES, ids=os.path.basename)
def test_every_argument_has_a_doc_and_a_working_default(path):
    for name, attrib in _user_args(path):
        assert attrib.get('doc', '').strip(), '%s: arg %s has no doc' % (os.path.basename(path), name)
        assert attrib.get('default', '') != '', '%s: arg %s has no default' % (os.path.basename(path), name)
    listed = subprocess.run(['roslaunch', '--ros-args', path], capture_output=True, text=True, timeout=60)
    assert listed.returncode == 0 and 'Required' not in listed.stdout, listed.stdout + listed.stderr


ENTRIES = ('sim.launch', 'Manager.launch', 'demo.launch', 'robot.launch', 'operator.launch')


@pytest.mark.parametrize('entry', ENTRIES)
def test_every_entry_launch_records_to_the_bag_asked(entry):
    asked = ['record:=true', 'bag:=/tmp/pirate_check.bag']
    assert '/record_run' not in _launch(entry).stdout          # off by default
    command = subprocess.run(['roslaunch', '--args', '/record_run', os.path.join(LAUNCH_DIR, entry)] + asked,
                             capture_output=True, text=True, timeout=60)
    assert command.returncode == 0, command.stderr
    assert '-O /tmp/pirate_check.bag' in command.stdout, command.stdout


def _launch(entry, *args):
    return subprocess.run(['roslaunch', '--nodes', os.path.join(LAUNCH_DIR, entry)] + list(args),
                          capture_output=True, text=True, timeout=60)


BAD_ARGS = [   # entry, argument, words of the error
    ('sim.launch', 'pipe_diameter:=100', 'only 90 and 110 mm'),
    ('sim.launch', 'pipe_diameter:=abc', 'pipe_diameter:=abc'),
    ('Manager.launch', 'pipe_diameter:=100', 'only 90 and 110 mm'),
    ('demo.launch', 'pipe_diameter:=75', 'only 90 and 110 mm'),
    ('robot.launch', 'robot:=simulated', 'use sim, fil or real'),
    ('robot.launch', 'rate:=0', 'above 0'),
    ('robot.launch', 'orientation:=up', 'a number of rad'),
    ('demo.launch', 'joints:=front_tilt 0.4', 'a YAML dict of joint: rad is needed'),
    ('Manager.launch', 'panel:=keyboard', 'use virtual, midi or none'),
    ('operator.launch', 'rate:=abc', 'rate:=abc: a real-time factor above 0'),
    ('operator.launch', 'world:=netwrk_90', 'the worlds there are: bend_down_90'),
    ('operator.launch', 'world:=straight_110', 'give pipe_diameter:=110'),
    ('operator.launch', 'robot:=fil', 'robot:=fil: use sim or real'),
    ('operator.launch', 'panel:=keyboard', 'panel:=keyboard: use virtual or midi or none'),
    ('operator.launch', 'rviz:=maybe', 'rviz:=maybe: true or false'),
]


@pytest.mark.parametrize('entry,arg,words', BAD_ARGS)
def test_bad_argument_values_stop_roslaunch_with_the_reason(entry, arg, words):
    nodes = _launch(entry, arg)
    assert nodes.returncode != 0
    assert words in nodes.stdout + nodes.stderr
    assert 'Traceback' not in nodes.stdout + nodes.stderr


@pytest.mark.parametrize('args,present,absent', [
    (['headless:=true'], ['/pirate_manager', '/sim_robot'], ['/virtual_panel', '/rviz']),
    (['rate:=5', 'gui:=false'], ['/virtual_panel'], ['/rviz']),
])
def test_sim_launch_headless_and_fast(args, present, absent):
    nodes = _launch('sim.launch', *args)
    assert nodes.returncode == 0, nodes.stderr
    for node in present:
        assert node in nodes.stdout
    for node in absent:
        assert node not in nodes.stdout


@pytest.mark.parametrize('entry,args,sim_time', [
    ('sim.launch', [], True),
    ('demo.launch', [], True),
    ('Manager.launch', ['robot:=sim'], True),
    ('robot.launch', ['robot:=sim'], True),
    ('Manager.launch', ['robot:=real'], False),
    ('Manager.launch', ['robot:=fil'], False),
    ('operator.launch', [], True),
    ('operator.launch', ['robot:=real'], False),
])
def test_the_simulated_robot_always_runs_on_simulated_time(entry, args, sim_time):
    """Every launch of the simulated robot sets /use_sim_time (its watchdogs
    judge silence on the lockstep clock, doc/clock.md); a real robot's stack keeps the wall clock."""
    dump = subprocess.run(['roslaunch', '--dump-params', os.path.join(LAUNCH_DIR, entry)] + args,
                          capture_output=True, text=True, timeout=60)
    assert dump.returncode == 0, dump.stderr
    assert ('/use_sim_time: true' in dump.stdout) == sim_time, dump.stdout


def test_the_pipe_diameter_reaches_the_manager_and_the_robot():
    dump = subprocess.run(['roslaunch', '--dump-params', os.path.join(LAUNCH_DIR, 'sim.launch'),
                           'pipe_diameter:=110', 'headless:=true'], capture_output=True, text=True, timeout=60)
    assert dump.returncode == 0, dump.stderr
    assert "/pirate_manager/pipe_diameter: 110" in dump.stdout
    assert "/sim_robot/pipe_diameter: 110" in dump.stdout


@pytest.mark.parametrize('entry', ['sim.launch', 'demo.launch', 'Manager.launch', 'robot.launch'])
def test_start_joints_reach_the_simulated_robot(entry):
    dump = subprocess.run(['roslaunch', '--dump-params', os.path.join(LAUNCH_DIR, entry),
                           'joints:={front_tilt: 0.4, bend_iv: -0.3}'], capture_output=True, text=True, timeout=60)
    assert dump.returncode == 0, dump.stderr
    assert '/sim_robot/joints/front_tilt: 0.4' in dump.stdout and '/sim_robot/joints/bend_iv: -0.3' in dump.stdout


def test_start_joints_reach_the_firmware_in_the_loop_robot():
    dump = subprocess.run(['roslaunch', '--dump-params', os.path.join(LAUNCH_DIR, 'robot.launch'), 'robot:=fil',
                           'joints:={bend_iv: -0.3}'], capture_output=True, text=True, timeout=60)
    assert dump.returncode == 0, dump.stderr
    assert '/fil_robot/joints/bend_iv: -0.3' in dump.stdout


def test_the_cameras_are_recorded_to_their_own_bag_only_when_asked():
    assert '/record_cameras' not in _launch('record.launch').stdout
    command = subprocess.run(['roslaunch', '--args', '/record_cameras', os.path.join(LAUNCH_DIR, 'record.launch'),
                              'cameras:=true', 'camera_bag:=/tmp/pirate_cameras_check.bag'],
                             capture_output=True, text=True, timeout=60)
    assert command.returncode == 0, command.stderr
    for part in ('-O /tmp/pirate_cameras_check.bag', '/pirate/front_camera/image_raw', '/pirate/rear_camera/image_raw',
                 '/pirate/inspection/findings'):
        assert part in command.stdout, command.stdout


# --- the operator launch ------------------------------------------------------

@pytest.mark.parametrize('args,present,absent', [
    (['world:=inspection_network_90'],
     ['/sim_robot', '/pirate_state', '/pirate_manager', '/mission_executive', '/virtual_panel', '/rviz_world'],
     ['/serial_node', '/midi_input']),
    (['robot:=real', 'panel:=midi'],
     ['/serial_node', '/pirate_manager', '/mission_executive', '/midi_input', '/midi_output', '/rviz'],
     ['/sim_robot', '/virtual_panel']),
    (['panel:=none', 'rviz:=false'], ['/pirate_manager', '/mission_executive'], ['/virtual_panel', '/rviz_world']),
])
def test_operator_launch_starts_the_whole_stack(args, present, absent):
    nodes = _launch('operator.launch', *args)
    assert nodes.returncode == 0, nodes.stderr
    for node in present:
        assert node in nodes.stdout, node
    for node in absent:
        assert node not in nodes.stdout, node


def test_operator_launch_composes_the_panel_in_the_manager_and_sends_the_world():
    dump = subprocess.run(['roslaunch', '--dump-params', os.path.join(LAUNCH_DIR, 'operator.launch'),
                           'world:=inspection_network_90'], capture_output=True, text=True, timeout=60)
    assert dump.returncode == 0, dump.stderr
    assert '/pirate_manager/panel: true' in dump.stdout
    assert '/sim_robot/world: inspection_network_90' in dump.stdout
    assert '/use_sim_time: true' in dump.stdout


def test_a_launch_without_a_panel_says_so():
    nodes = _launch('operator.launch', 'panel:=none')
    assert nodes.returncode == 0
    assert 'no operator panel (panel:=none)' in nodes.stderr


def test_sim_launch_puts_the_robot_in_the_world_asked():
    dump = subprocess.run(['roslaunch', '--dump-params', os.path.join(LAUNCH_DIR, 'sim.launch'),
                           'world:=network_90', 'headless:=true'], capture_output=True, text=True, timeout=60)
    assert dump.returncode == 0, dump.stderr
    assert '/sim_robot/world: network_90' in dump.stdout


@pytest.mark.parametrize('entry', ['operator.launch', 'sim.launch', 'Manager.launch', 'demo.launch'])
def test_the_managers_death_leaves_the_stack_running(entry):
    """Ctrl-C or a crash of pirate_manager: it is started again, nothing else ends."""
    from roslaunch.config import load_config_default
    config = load_config_default([os.path.join(LAUNCH_DIR, entry)], None, verbose=False)
    manager = [n for n in config.nodes if n.name == 'pirate_manager']
    assert manager and manager[0].respawn and not manager[0].required
