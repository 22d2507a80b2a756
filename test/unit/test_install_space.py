"""The package as `catkin_make install` installs it (the install space a
.deb is made from) finds its config, worlds, URDF and launch files there,
with the source tree nowhere on the path.

One install of a copy of the package (its tracked top-level folders) into a
temporary workspace, then commands run under that install space's
setup.bash only.
"""
import os
import shutil
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
#: What the package is made of: copied, not linked, so nothing reaches back into this tree.
SOURCES = ('CMakeLists.txt', 'package.xml', 'setup.py', 'action', 'cfg', 'config', 'launch', 'msg', 'nodes',
           'rviz', 'src', 'srv', 'urdf')


def _run(command, cwd, env=None):
    done = subprocess.run(['bash', '-c', command], cwd=cwd, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, universal_newlines=True, timeout=600)
    assert done.returncode == 0, '%s\n%s' % (command, done.stdout[-4000:])
    return done.stdout


def _clean_env():
    """This shell's environment without this tree's workspaces: only ROS
    itself (/opt/ros, or Debian's /usr) is left for the install space's
    setup.bash to extend."""
    env = {k: v for k, v in os.environ.items()
           if k not in ('PYTHONPATH', 'ROS_PACKAGE_PATH', 'CMAKE_PREFIX_PATH', 'LD_LIBRARY_PATH', 'PKG_CONFIG_PATH')
           and not k.startswith('ROS_') or k in ('ROS_MASTER_URI', 'ROS_IP', 'ROS_HOSTNAME')}
    env['PATH'] = os.path.dirname(sys.executable) + ':/usr/bin:/bin'
    return env


def _debian_layout():
    """Whether this interpreter's setuptools installs in Debian's layout
    (lib/python3/dist-packages; Debian's and Ubuntu's do, PyPI's does not),
    as catkin assumes on a Debian system."""
    from setuptools.command.install import install
    return any(option[0].startswith('install-layout') for option in install.user_options)


@pytest.fixture(scope='module')
def install(tmp_path_factory):
    """The install space of a fresh workspace holding a copy of the package."""
    if shutil.which('catkin_make') is None:
        pytest.fail('catkin_make not found (Debian package catkin)')
    ws = str(tmp_path_factory.mktemp('install_ws'))
    package = os.path.join(ws, 'src', 'pirate')
    os.makedirs(package)
    for name in SOURCES:
        source = os.path.join(ROOT, name)
        copy = shutil.copytree if os.path.isdir(source) else shutil.copy
        copy(source, os.path.join(package, name))
    _run('catkin_make install -DPYTHON_EXECUTABLE=%s -DSETUPTOOLS_DEB_LAYOUT=%s > build.log 2>&1 '
         '|| { tail -40 build.log; exit 1; }' % (sys.executable, 'ON' if _debian_layout() else 'OFF'), ws, _clean_env())
    shutil.rmtree(os.path.join(ws, 'src'))       # the install must stand alone
    shutil.rmtree(os.path.join(ws, 'devel'))
    return os.path.join(ws, 'install')


def in_install(install, command):
    """Run ``command`` under the install space's setup.bash, ROS's own
    packages kept on the package path (where they are not in a workspace
    that setup.bash chains: Debian's /usr/share for PyPI's rospkg)."""
    ros = [p for p in os.environ.get('ROS_PACKAGE_PATH', '').split(os.pathsep) if p and not p.startswith(ROOT)]
    keep = ' && export ROS_PACKAGE_PATH=$ROS_PACKAGE_PATH:%s' % os.pathsep.join(ros) if ros else ''
    return _run('source %s/setup.bash%s && %s' % (install, keep, command), install, _clean_env())


def test_the_library_finds_its_data_in_the_install_space(install):
    out = in_install(install, '''python3 -c "
from pirate import paths
from pirate.sim import twin_model
from pirate.world import network
world = network.load(network.world_path('network_90'))
assert twin_model.model_xml(world, twin_model.load_config(), 0.0).startswith('<mujoco')
print(paths.PACKAGE_DIR)
import pirate; print(pirate.__file__)"''')
    package_dir, library = out.split()[-2:]
    assert package_dir == os.path.join(install, 'share', 'pirate')
    assert library.startswith(install + os.sep)
    for data in ('config/twin.yaml', 'config/worlds/straight_90.yaml', 'urdf/pirate.urdf', 'launch/demo.launch',
                 'rviz'):
        assert os.path.exists(os.path.join(package_dir, data)), data


def test_a_node_runs_from_the_install_space(install):
    """plan_mission reads config/supervisory.yaml, the guards and a world."""
    out = in_install(install, 'rosrun pirate plan_mission inspection_90 launch_pit target')
    assert 'launch_pit' in out


def test_launch_files_resolve_from_the_install_space(install):
    out = in_install(install, 'roslaunch --files pirate demo.launch')
    files = out.split()
    assert os.path.join(install, 'share', 'pirate', 'launch', 'demo.launch') in files
    assert [f for f in files if f.startswith(ROOT + os.sep)] == []     # nothing from this tree
