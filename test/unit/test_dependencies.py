"""What the code imports and runs is what the install lists declare.

scripts/debian-packages.txt is what `make test` / `make demo` install on a
fresh machine; package.xml is what rosdep and catkin read. Both are checked
against the code, not against what this machine happens to have: a machine
with extra packages once hid a missing entry (on a fresh CI machine the
serial node died with "No module named 'diagnostic_msgs'": on Debian the
ros-*-msgs packages hold only the .msg files, the Python modules come in
python3-*-msgs; and `rosrun` is in rosbash, which nothing else pulls in).
"""
import functools
import importlib.util
import os
import re
import sys
import sysconfig
import xml.etree.ElementTree as ElementTree

ROOT = os.path.join(os.path.dirname(__file__), '..', '..')
CODE_DIRS = ('src', 'nodes', 'test', 'bench')
#: Executables without a .py suffix live here.
SCRIPT_DIRS = ('nodes', 'bench')

#: Third-party Python modules the code imports, and their Debian packages
#: (message packages are python3-<name with dashes>, checked by rule).
MODULES = {
    'rospy': 'python3-rospy', 'actionlib': 'python3-actionlib', 'rosbag': 'python3-rosbag',
    'rosgraph': 'python3-rosgraph', 'roslaunch': 'python3-roslaunch', 'roslib': 'python3-roslib',
    'rosnode': 'python3-rosnode', 'rospkg': 'python3-rospkg', 'rostest': 'python3-rostest',
    'tf2_ros': 'python3-tf2-ros', 'yaml': 'python3-yaml', 'serial': 'python3-serial',
    'pygame': 'python3-pygame', 'numpy': 'python3-numpy', 'matplotlib': 'python3-matplotlib',
    'PIL': 'python3-pil', 'hypothesis': 'python3-hypothesis', 'pytest': 'python3-pytest',
    'diagnostic_updater': 'python3-diagnostic-updater', 'dynamic_reconfigure': 'python3-dynamic-reconfigure',
    'rosdep2': 'python3-rosdep2', 'setuptools': 'python3-setuptools',
    'distributed': 'python3-distributed',
    'cv2': 'python3-opencv',
}
#: Third-party modules from PyPI (scripts/pip-requirements.txt, installed
#: into .venv by scripts/ensure_deps) and their rosdep keys in package.xml.
PIP_MODULES = {'mujoco': ('mujoco', 'python3-mujoco-pip')}
#: The commands the Python code runs as subprocesses, and their Debian packages.
COMMANDS = {
    'rosrun': 'rosbash', 'roslaunch': 'python3-roslaunch', 'roscore': 'python3-roslaunch',
    'rosparam': 'python3-rosparam', 'rostest': 'python3-rostest',
    'check_urdf': 'liburdfdom-tools', 'Xvfb': 'xvfb',
    'catkin_make': 'catkin', 'catkin_lint': 'catkin-lint',
}

#: 'import x' or 'from x[.y] import', capturing x (not a docstring line 'from board 22').
TOP_IMPORT = re.compile(r'^\s*(?:import\s+(\w+)|from\s+(\w+)[\w.]*\s+import\b)', re.MULTILINE)
#: A command at the head of a subprocess argument list: ['rosrun', ...
SUBPROCESS_COMMAND = re.compile(r"""\[\s*['"]([A-Za-z_]\w*)['"]\s*,""")


@functools.lru_cache(maxsize=None)
def _python_sources():
    """{path: text} of every Python file of the project, read once per session."""
    sources = {}
    for top in CODE_DIRS:
        for folder, _, files in os.walk(os.path.join(ROOT, top)):
            for name in files:
                if name.endswith('.py') or (top in SCRIPT_DIRS and '.' not in name):
                    path = os.path.join(folder, name)
                    with open(path, encoding='utf-8') as source:
                        sources[path] = source.read()
    return sources


def _imported():
    return {a or b for text in _python_sources().values() for a, b in TOP_IMPORT.findall(text)}


def _is_standard_library(module):
    """Whether the running interpreter's standard library holds ``module``
    (a top-level name; found where it lies, so on Python 3.8 too)."""
    if module in sys.builtin_module_names:
        return True
    spec = importlib.util.find_spec(module)
    if spec is None or spec.origin is None:
        return False
    if spec.origin in ('built-in', 'frozen'):
        return True
    stdlib = os.path.realpath(sysconfig.get_paths()['stdlib'])
    path = os.path.realpath(spec.origin)
    return path.startswith(stdlib + os.sep) and not {'site-packages', 'dist-packages'} & set(path.split(os.sep))


def _third_party():
    local = {'pirate'} | {os.path.splitext(os.path.basename(p))[0] for p in _python_sources()}
    return {m for m in _imported() - local if not _is_standard_library(m)}


def _message_packages():
    return {m for m in _third_party() if m.endswith('_msgs')}


def _commands():
    return {c for text in _python_sources().values() for c in SUBPROCESS_COMMAND.findall(text)
            if c.startswith('ros') or c in COMMANDS}


def _package_xml_deps():
    tree = ElementTree.parse(os.path.join(ROOT, 'package.xml'))
    tags = ('depend', 'build_depend', 'exec_depend', 'test_depend')
    return {e.text.strip() for tag in tags for e in tree.getroot().iter(tag)}


def _debian_packages():
    with open(os.path.join(ROOT, 'scripts', 'debian-packages.txt')) as listing:
        return {line.split()[0] for line in listing if line.strip() and not line.startswith('#')}


def test_the_scans_see_what_we_know_we_use():
    assert {'diagnostic_msgs', 'sensor_msgs', 'actionlib_msgs'} <= _message_packages()
    assert {'rospy', 'actionlib', 'yaml'} <= _third_party()
    assert {'rosrun', 'roslaunch', 'roscore'} <= _commands()
    assert 'board' not in _imported()   # a docstring line "from board 22 ..." is no import


def test_every_imported_message_package_is_in_package_xml():
    missing = _message_packages() - _package_xml_deps()
    assert not missing, 'imported but not declared in package.xml: %s' % sorted(missing)


def test_every_imported_message_package_has_its_python_module_listed():
    wanted = {'python3-' + name.replace('_', '-') for name in _message_packages()}
    missing = wanted - _debian_packages()
    assert not missing, 'add to scripts/debian-packages.txt: %s' % sorted(missing)


def _pip_requirements():
    with open(os.path.join(ROOT, 'scripts', 'pip-requirements.txt')) as listing:
        return {re.split(r'[=<>~ ]', line.strip())[0] for line in listing if line.strip() and not line.startswith('#')}


def test_every_pip_module_is_required_and_declared_for_rosdep():
    used = _third_party() & set(PIP_MODULES)
    assert 'mujoco' in used
    assert {PIP_MODULES[m][0] for m in used} <= _pip_requirements()
    assert {PIP_MODULES[m][1] for m in used} <= _package_xml_deps()


def test_every_third_party_module_has_its_package_listed():
    modules = _third_party() - _message_packages() - set(PIP_MODULES)
    unknown = modules - set(MODULES)
    assert not unknown, 'say which Debian package installs %s in MODULES' % sorted(unknown)
    missing = {MODULES[m] for m in modules} - _debian_packages()
    assert not missing, 'add to scripts/debian-packages.txt: %s' % sorted(missing)


def test_every_command_run_has_its_package_listed():
    unknown = _commands() - set(COMMANDS)
    assert not unknown, 'say which Debian package installs %s in COMMANDS' % sorted(unknown)
    missing = {COMMANDS[c] for c in _commands()} - _debian_packages()
    assert not missing, 'add to scripts/debian-packages.txt: %s' % sorted(missing)


#: The ROS packages launch files start nodes from, and the Debian packages
#: that hold their package.xml (roslaunch finds a package by it: on Debian
#: the aggregator's binary is in -tools, its package.xml in -dev; a fresh
#: CI machine had only the first and every launch with the aggregator died).
LAUNCHED_PACKAGES = {
    'diagnostic_aggregator': 'libdiagnostic-aggregator-dev',
    'robot_state_publisher': 'ros-robot-state-publisher',
    'rosbag': 'python3-rosbag', 'rviz': 'rviz',
}
LAUNCH_PKG = re.compile(r'\bpkg="([^"$]+)"')


def _launched_packages():
    found = set()
    for top in ('launch', os.path.join('test', 'rostest')):
        for folder, _, files in os.walk(os.path.join(ROOT, top)):
            for name in files:
                if name.endswith(('.launch', '.test')):
                    with open(os.path.join(folder, name), encoding='utf-8') as launch:
                        found |= set(LAUNCH_PKG.findall(launch.read()))
    return found - {'pirate'}


def test_every_launched_package_has_its_manifest_package_listed():
    launched = _launched_packages()
    assert 'diagnostic_aggregator' in launched
    unknown = launched - set(LAUNCHED_PACKAGES)
    assert not unknown, 'say which Debian package holds the package.xml of %s' % sorted(unknown)
    missing = {LAUNCHED_PACKAGES[p] for p in launched} - _debian_packages()
    assert not missing, 'add to scripts/debian-packages.txt: %s' % sorted(missing)
    undeclared = launched - _package_xml_deps()
    assert not undeclared, 'declare in package.xml: %s' % sorted(undeclared)
