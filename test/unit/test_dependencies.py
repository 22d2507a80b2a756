"""Every ROS message package the Python code imports is declared twice: in
package.xml (for rosdep and catkin) and in scripts/debian-packages.txt as
its Debian python3-*-msgs package, which `make test` / `make demo` install.

On Debian the ros-*-msgs packages hold only the .msg files; the Python
modules come in python3-*-msgs. A machine that happened to have them
installed hid a missing entry once (the serial node died on a fresh CI
machine with "No module named 'diagnostic_msgs'"), so the lists are checked
against the code, not against what this machine has.
"""
import os
import re
import xml.etree.ElementTree as ElementTree

ROOT = os.path.join(os.path.dirname(__file__), '..', '..')
CODE_DIRS = ('src', 'nodes', 'test', 'bench')
IMPORT = re.compile(r'^\s*(?:from|import)\s+([a-z0-9_]+_msgs)\b', re.MULTILINE)


def _python_files():
    for top in CODE_DIRS:
        for folder, _, files in os.walk(os.path.join(ROOT, top)):
            for name in files:
                path = os.path.join(folder, name)
                if name.endswith('.py') or (top == 'nodes' and '.' not in name):
                    yield path


def _imported_msg_packages():
    found = set()
    for path in _python_files():
        with open(path, encoding='utf-8') as source:
            found.update(IMPORT.findall(source.read()))
    return found


def _package_xml_deps():
    tree = ElementTree.parse(os.path.join(ROOT, 'package.xml'))
    tags = ('depend', 'build_depend', 'exec_depend', 'test_depend')
    return {e.text.strip() for tag in tags for e in tree.getroot().iter(tag)}


def _debian_packages():
    with open(os.path.join(ROOT, 'scripts', 'debian-packages.txt')) as listing:
        return {line.split()[0] for line in listing if line.strip() and not line.startswith('#')}


def test_the_scan_finds_the_message_packages_we_know_we_use():
    assert {'diagnostic_msgs', 'sensor_msgs', 'actionlib_msgs'} <= _imported_msg_packages()


def test_every_imported_message_package_is_in_package_xml():
    missing = _imported_msg_packages() - _package_xml_deps()
    assert not missing, 'imported but not declared in package.xml: %s' % sorted(missing)


def test_every_imported_message_package_has_its_python_module_installed_by_ensure_deps():
    wanted = {'python3-' + name.replace('_', '-') for name in _imported_msg_packages()}
    missing = wanted - _debian_packages()
    assert not missing, 'add to scripts/debian-packages.txt: %s' % sorted(missing)
