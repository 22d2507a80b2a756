"""config/diagnostics.yaml: which analyzer group takes which status name,
read as diagnostic_aggregator's GenericAnalyzer reads it (``startswith``,
``contains``, ``name``: any one matches). No ROS."""
import os

import pytest
import yaml

CONFIG = os.path.join(os.path.dirname(__file__), '..', '..', 'config', 'diagnostics.yaml')


def groups_of(status_name):
    """Paths of every analyzer group that takes ``status_name``."""
    with open(CONFIG) as f:
        analyzers = yaml.safe_load(f)['analyzers']
    found = []
    for analyzer in analyzers.values():
        def listed(key):
            value = analyzer.get(key, [])
            return [value] if isinstance(value, str) else value
        if (any(status_name.startswith(s) for s in listed('startswith'))
                or any(c in status_name for c in listed('contains'))
                or status_name in listed('name')):
            found.append(analyzer['path'])
    return found


@pytest.mark.parametrize('status_name', (
    'serial_node: pirate: serial link /dev/ttyACM0',   # our host
    'rosserial_python',                                 # rosserial_python's own (errors only)
    'pirate_state: Small State'))                      # the stream, whichever host
def test_the_link_group_takes_either_host(status_name):
    assert 'Link' in groups_of(status_name)


def test_the_small_state_stays_in_the_robot_group_too():
    assert sorted(groups_of('pirate_state: Small State')) == ['Link', 'Robot']
