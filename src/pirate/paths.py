"""Where the package's data lives, for code that runs from the source tree.

The library is imported from ``<package>/src/pirate`` (the catkin devel
space links to the source), so the package's ``config/`` and ``urdf/``
folders are two levels above this file, wherever a module sits below it.
"""
import os

PACKAGE_DIR = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
CONFIG_DIR = os.path.join(PACKAGE_DIR, 'config')
