"""The library's layers and its ROS edges, checked on the source (no ROS needed).

Each package of src/pirate is a layer (report 3.2): robot I/O -> state ->
sequencer -> supervisory; panel, link, sim and viz beside them; manager
composes the sequencer with the panel (report Fig 4.1); docs (the tables
``make docs`` writes from the code) reads the layers it documents; testing
(the rigs tests and bench/ build) sits on top of everything. :data:`ALLOWED`
says which layers each may import; nothing else imports ``pirate.testing``.
Only the modules in :data:`ROS_MODULES` import ROS (rospy, actionlib,
message packages, ``pirate.msg`` ...), and they are named ``*_node.py`` or
``*_ros.py``: the rest of the library imports and runs without ROS.

Imports are read with :mod:`ast`, function-local ones too.
"""
import ast
import os

import pytest

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), '..', '..'))
LIBRARY = os.path.join(ROOT, 'src', 'pirate')

#: The top-level modules and the generated messages every layer may use; any
#: other top-level module is a layer of its own.
BASE = 'base'
BASE_MODULES = ('names', 'paths', 'health', 'msg', 'srv', 'cfg')

#: Which layers each layer may import (its own and ``base`` always).
ALLOWED = {
    BASE: set(),
    'robot': set(),
    'world': set(),
    'state': {'robot'},
    'sequencer': {'robot', 'state'},
    'supervisory': {'robot', 'state', 'sequencer', 'world'},
    'panel': {'robot', 'state', 'sequencer', 'supervisory'},
    'link': {'robot'},
    'camera': set(),      # images and camera info as ROS messages, the real cameras' node
    'sim': {'robot', 'state', 'world', 'camera'},
    'viz': {'robot', 'state', 'sequencer', 'supervisory', 'world', 'sim'},   # sim: the twin's pipe geometry
    'manager': {'robot', 'state', 'sequencer', 'panel'},
    'docs': {'robot', 'state', 'sequencer', 'supervisory', 'world', 'panel', 'link', 'sim', 'viz', 'camera'},
    'sweep': {'world'},   # the runner of the twin benches; a bench's cases load it
    'inspection': {'robot', 'state', 'world', 'supervisory'},   # findings placed on the map, the report
    'launch_check': {'world'},   # operator.launch's arguments: the worlds there are
    'testing': {'robot', 'state', 'sequencer', 'supervisory', 'world', 'panel', 'link', 'sim', 'viz',
                'manager', 'camera', 'inspection', 'sweep'},   # sweep: drawn robots as a sweep's cases
}

#: The modules that import ROS. Each is named *_node.py or *_ros.py.
ROS_MODULES = (
    'pirate.camera.images_ros',
    'pirate.camera.v4l2_node',
    'pirate.link.host_ros',
    'pirate.link.service_bridge_ros',
    'pirate.inspection.inspection_node',
    'pirate.inspection.job_node',
    'pirate.manager.action_server_ros',
    'pirate.manager.goal_owner_ros',
    'pirate.manager.manager_node',
    'pirate.panel.mapper_ros',
    'pirate.panel.midi_node',
    'pirate.panel.virtual_node',
    'pirate.sim.robot_node',
    'pirate.state.clock_ros',
    'pirate.state.state_node',
    'pirate.supervisory.executive_node',
    'pirate.supervisory.goal_client_ros',
    'pirate.supervisory.mission_node',
    'pirate.supervisory.route_client_ros',
    'pirate.testing.fil_node',
    'pirate.viz.bag_ros',
    'pirate.viz.pose_node',
    'pirate.viz.world_node',
)

#: Python packages of ROS; any ``*_msgs`` / ``*_srvs`` package is one too.
ROS_PACKAGES = {
    'actionlib', 'diagnostic_updater', 'dynamic_reconfigure', 'genpy', 'message_filters', 'rosbag',
    'rosgraph', 'roslaunch', 'roslib', 'rosnode', 'rosparam', 'rospkg', 'rospy', 'rosserial_python',
    'rosservice', 'rostest', 'rostopic', 'rosunit', 'tf', 'tf2_ros',
}
#: The package's generated ROS modules.
ROS_GENERATED = ('pirate.msg', 'pirate.srv', 'pirate.cfg')

#: Executables in nodes/ that may import pirate.testing: the FIL robot is a rig.
RIG_EXECUTABLES = ('fil_robot',)


def module_name(path):
    """'pirate.sequencer.pabs.junction' for src/pirate/sequencer/pabs/junction.py."""
    relative = os.path.relpath(path, os.path.dirname(LIBRARY))[:-len('.py')]
    parts = relative.split(os.sep)
    return '.'.join(parts[:-1] if parts[-1] == '__init__' else parts)


def layer_of(module):
    """The layer of a ``pirate...`` module name: its package under pirate, or :data:`BASE`."""
    parts = module.split('.')
    if len(parts) < 2 or parts[1] in BASE_MODULES:
        return BASE
    return parts[1]


def imports(module, source):
    """[(line, imported module name)] of every import in ``source``, function-local ones too.

    ``from pirate import names`` yields 'pirate.names'; relative imports are
    resolved as from the module file ``module`` (the library has none).
    """
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found.extend((node.lineno, alias.name) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            found.extend((node.lineno, name) for name in _from_names(module, node))
    return sorted(found)


def _from_names(module, node):
    base = node.module or ''
    if node.level:
        base = '.'.join(module.split('.')[:-node.level] + ([base] if base else []))
    if base == 'pirate':
        return ['pirate.' + alias.name for alias in node.names]
    return [base]


def is_ros(name):
    """True for a module of ROS: rospy, actionlib, a message package, pirate.msg ..."""
    top = name.split('.')[0]
    return (top in ROS_PACKAGES or top.endswith(('_msgs', '_srvs'))
            or any(name == g or name.startswith(g + '.') for g in ROS_GENERATED))


def layer_violations(module, source):
    """Why each pirate import of ``module`` crosses the layers; [] when none does."""
    layer = layer_of(module)
    allowed = ALLOWED[layer] | {layer, BASE}
    return ['%s line %d imports %s: %s may import %s' % (module, line, name, layer, ', '.join(sorted(allowed)))
            for line, name in imports(module, source)
            if (name == 'pirate' or name.startswith('pirate.')) and layer_of(name) not in allowed]


def ros_violations(module, source):
    """Why each ROS import of ``module`` is not allowed; [] when none is."""
    if module in ROS_MODULES:
        return []
    return ['%s line %d imports %s: only the modules of ROS_MODULES import ROS' % (module, line, name)
            for line, name in imports(module, source) if is_ros(name)]


def _library():
    """{module name: source} of every module in src/pirate."""
    found = {}
    for folder, _, files in os.walk(LIBRARY):
        for name in files:
            if name.endswith('.py'):
                path = os.path.join(folder, name)
                with open(path) as source:
                    found[module_name(path)] = source.read()
    return found


LIBRARY_MODULES = _library()


def test_every_package_of_the_library_has_its_row_in_the_table():
    packages = {layer_of(m) for m in LIBRARY_MODULES}
    assert packages == set(ALLOWED), 'packages without a row: %s; rows without a package: %s' % (
        sorted(packages - set(ALLOWED)), sorted(set(ALLOWED) - packages))


def test_each_layer_imports_only_the_layers_below_it():
    found = [v for module, source in sorted(LIBRARY_MODULES.items()) for v in layer_violations(module, source)]
    assert not found, '\n'.join(found)


def test_only_the_ros_modules_import_ros():
    found = [v for module, source in sorted(LIBRARY_MODULES.items()) for v in ros_violations(module, source)]
    assert not found, '\n'.join(found)


def test_each_ros_module_exists_imports_ros_and_says_so_in_its_name():
    for module in ROS_MODULES:
        assert module in LIBRARY_MODULES, '%s is listed in ROS_MODULES and does not exist' % module
        assert any(is_ros(name) for _, name in imports(module, LIBRARY_MODULES[module])), (
            '%s is listed in ROS_MODULES and imports no ROS' % module)
        assert module.endswith(('_node', '_ros')), (
            '%s imports ROS: name it *_node.py or *_ros.py' % module)


def test_no_executable_but_the_rigs_imports_the_test_rigs():
    folder = os.path.join(ROOT, 'nodes')
    found = []
    for name in sorted(os.listdir(folder)):
        with open(os.path.join(folder, name)) as source:
            found += ['nodes/%s line %d imports %s' % (name, line, module)
                      for line, module in imports('nodes.' + name, source.read())
                      if layer_of(module) == 'testing' and name not in RIG_EXECUTABLES]
    assert not found, '\n'.join(found)


@pytest.mark.parametrize('module, source, wrong', [
    ('pirate.sequencer.wiring', 'def panel():\n    from pirate.panel.mapper_ros import MapperRos\n',
     'pirate.sequencer.wiring line 2 imports pirate.panel.mapper_ros'),
    ('pirate.link.relay', 'from pirate.testing import fil\n', 'pirate.link.relay line 1 imports pirate.testing'),
    ('pirate.robot.tables', 'import pirate.state.feed\n', 'pirate.robot.tables line 1 imports pirate.state.feed'),
    ('pirate.state.feed', 'from pirate import sequencer\n', 'pirate.state.feed line 1 imports pirate.sequencer'),
    ('pirate.sim.twin', 'from ..supervisory import truth\n', 'pirate.sim.twin line 1 imports pirate.supervisory'),
    ('pirate.names', 'from pirate.robot import tables\n', 'pirate.names line 1 imports pirate.robot'),
])
def test_a_module_that_crosses_the_layers_is_named_with_its_import(module, source, wrong):
    found = layer_violations(module, source)
    assert len(found) == 1 and found[0].startswith(wrong + ':'), found


@pytest.mark.parametrize('module, source, wrong', [
    ('pirate.state.assembler', 'def now():\n    import rospy\n    return rospy.get_time()\n',
     'pirate.state.assembler line 2 imports rospy'),
    ('pirate.sequencer.server', 'from std_msgs.msg import String\n',
     'pirate.sequencer.server line 1 imports std_msgs.msg'),
    ('pirate.panel.mapper', 'from pirate.msg import MidiInput\n', 'pirate.panel.mapper line 1 imports pirate.msg'),
    ('pirate.panel.mapper', 'from pirate import srv\n', 'pirate.panel.mapper line 1 imports pirate.srv'),
    ('pirate.viz.plot', 'import rosbag.bag\n', 'pirate.viz.plot line 1 imports rosbag.bag'),
])
def test_a_pure_module_that_imports_ros_is_named_with_its_import(module, source, wrong):
    found = ros_violations(module, source)
    assert len(found) == 1 and found[0].startswith(wrong + ':'), found


@pytest.mark.parametrize('module, source', [
    ('pirate.supervisory.executive', 'from pirate.sequencer import goals\nfrom pirate.world import network\n'),
    ('pirate.testing.harness', 'from pirate.manager import manager_node\nimport threading\n'),
    ('pirate.state.clock_ros', 'import rospy\n'),
    ('pirate.robot.units', 'import math\nfrom pirate import names\n'),
])
def test_imports_along_the_layers_pass(module, source):
    assert layer_violations(module, source) == [] and ros_violations(module, source) == []
