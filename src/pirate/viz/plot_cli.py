"""plot_run: turn a run's rosbag into a PNG like the report's Figs 6.1-6.7.

    rosrun pirate plot_run RUN.bag [-o RUN.png] [--guards config/guards_90.yaml]

Without --guards, the guard lines come from config/guards_<D>.yaml for the
pipe diameter D the run's goal named, when that file exists; a run without
one is plotted without guard lines. Prints one line per primitive marker.
A run of a mission also gets RUN_mission.png: the distance along
the route against time, each PAB marked (pirate.viz.mission_plot).
"""
import argparse
import os
import sys

import yaml

from pirate import paths
from pirate.viz import bag_ros, mission_plot, plot


def _default_guards(diameter):
    """config/guards_<diameter>.yaml of the pirate package, None if absent."""
    path = os.path.join(paths.CONFIG_DIR, 'guards_%d.yaml' % diameter)
    return path if os.path.exists(path) else None


def _guard_config(path, diameters):
    """(parsed guard YAML, its path): ``path``, else the goal pipe's, else None."""
    if path is None and diameters:
        path = _default_guards(diameters[-1])
    if path is None:
        return None, None
    with open(path) as f:
        return yaml.safe_load(f), path


def plot_bag(bag_path, output, guards=None, title=None):
    """Plot the run in ``bag_path`` to ``output``: (run, panels, config path).

    ``guards`` is a guard YAML path; None picks the goal pipe's. Raises
    OSError, ValueError, yaml.YAMLError or bag_ros.BagError on bad input.
    """
    run, drawn, config_path, _ = plot_bag_and_mission(bag_path, output, guards, title, mission=False)
    return run, drawn, config_path


def plot_bag_and_mission(bag_path, output, guards=None, title=None, mission=True):
    """:func:`plot_bag`, and the bag's mission (if it holds one and ``mission``)
    to ``OUTPUT_mission.png`` on the same time axis: (run, panels, config path,
    MissionRun or None)."""
    run, diameters = bag_ros.read_run(bag_path)
    config, config_path = _guard_config(guards, diameters)
    lines = plot.guard_lines(config, [p for _, p in run.markers])
    found = bag_ros.read_mission(bag_path, run.start_s) if mission else None
    xlim = shared_axis(run, found)
    drawn, _ = plot.plot_run(run, output, lines, title, xlim)
    if found is not None:
        mission_plot.plot_mission(found, os.path.splitext(output)[0] + '_mission.png', xlim=xlim)
    return run, drawn, config_path, found


def shared_axis(run, mission):
    """(0, s) covering the run and its mission, or None without a mission."""
    if mission is None:
        return None
    return 0.0, max([run.times[-1]] + list(mission.times) + [t for t, _ in mission.events])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('bag', help='rosbag recorded by launch/record.launch')
    parser.add_argument('-o', '--output', help='PNG to write (default: the bag with .png)')
    parser.add_argument('--guards', help='guard config YAML (default: by the goal\'s pipe)')
    parser.add_argument('--title', help='figure title (default: what ran, the pipe, how it ended, the bag)')
    args = parser.parse_args(argv)
    output = args.output or os.path.splitext(args.bag)[0] + '.png'
    try:
        run, _, config_path, mission = plot_bag_and_mission(args.bag, output, args.guards, args.title)
    except (OSError, ValueError, yaml.YAMLError, bag_ros.BagError) as error:
        sys.exit('plot_run: %s' % error)
    for i, (t, primitive) in enumerate(run.markers, 1):
        print('t%d %7.2f s  %s' % (i, t, primitive))
    print('wrote %s (%d samples, %d primitives, guards: %s)'
          % (output, len(run.times), len(run.markers), config_path or 'none'))
    if mission is not None:
        mission_output = os.path.splitext(output)[0] + '_mission.png'
        print('wrote %s (%s: %d PABs, %d estimates along the route)'
              % (mission_output, mission.title, len(mission.markers), len(mission.times)))
