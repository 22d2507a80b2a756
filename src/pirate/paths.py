"""Where the package's data (config/, urdf/, launch/, rviz/) lives.

From the source tree or a catkin devel space (which links to the source)
the library is imported from ``<package>/src/pirate``: the package is two
folders up. From an install space or a .deb it is imported from
``<prefix>/lib/python3*/dist-packages/pirate`` and the data was installed
to ``<prefix>/share/pirate``. Each has the package's ``package.xml``.
"""
import os

PACKAGE = 'pirate'
_HERE = os.path.dirname(os.path.abspath(__file__))


def package_dir(module_dir=_HERE):
    """The package's folder for the library at ``module_dir``: the source
    tree above it, else ``share/pirate`` of the prefix it is installed in."""
    source = os.path.normpath(os.path.join(module_dir, '..', '..'))
    if os.path.isfile(os.path.join(source, 'package.xml')):
        return source
    folder = module_dir
    while os.path.dirname(folder) != folder:
        folder = os.path.dirname(folder)
        share = os.path.join(folder, 'share', PACKAGE)
        if os.path.isfile(os.path.join(share, 'package.xml')):
            return share
    raise RuntimeError('%s: no package.xml in %s nor in share/%s above %s (an incomplete install?)'
                       % (PACKAGE, source, PACKAGE, module_dir))


PACKAGE_DIR = package_dir()
CONFIG_DIR = os.path.join(PACKAGE_DIR, 'config')
