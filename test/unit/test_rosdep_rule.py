"""rosdep.yaml's rule is one that rosdep sees as satisfied once installed:
its pip detection (rosdep2.platforms.pip.pip_detect) finds every package
the rule installs, in this interpreter's environment as `pip freeze` lists
it, and in one that holds MuJoCo 3.2.3 (Ubuntu 20.04's Python 3.8)."""
import os

import pytest
import yaml
from rosdep2.platforms import pip as rosdep_pip

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))


def pip_packages():
    """[(platform, [package, ...])] of every pip rule in rosdep.yaml."""
    with open(os.path.join(ROOT, 'rosdep.yaml')) as stream:
        rules = yaml.safe_load(stream)
    found = []

    def walk(where, node):
        if 'pip' in node:
            found.append((where, node['pip']['packages']))
        else:
            for key, child in node.items():
                walk('%s %s' % (where, key), child)
    for key, platforms in rules.items():
        walk(key, platforms)
    return found


RULES = pip_packages()


def test_the_rule_installs_mujoco_on_debian_and_ubuntu():
    assert {where.split()[1] for where, _ in RULES} == {'debian', 'ubuntu'}
    assert all('mujoco' in packages for _, packages in RULES)


@pytest.mark.parametrize('where, packages', RULES)
def test_rosdep_sees_the_rule_satisfied_once_installed(where, packages):
    focal = 'numpy==1.17.4\nmujoco==3.2.3\nPyYAML==5.3.1\n'
    assert rosdep_pip.pip_detect(packages, exec_fn=lambda command: focal) == packages, where
    assert rosdep_pip.pip_detect(packages) == packages, where       # this interpreter's pip, as installed
