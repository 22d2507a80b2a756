"""``rosrun pirate plan_mission MAP FROM TO [VIA ...]``: print a route's plan.

MAP is a world file (config/worlds/, pirate.world.network) or the name of
one there; FROM, TO (and more points to visit in order) are point names of
that map. Prints the PAB goals the route needs, with where each starts and
should end, before anything moves, and says on stderr when the Pirate
Server cannot run a step of it yet (a junction the PAB does not take).
Needs no ROS master. Exit 0 with a plan, 2 when the map or the route is
refused (the reason on stderr).
"""
import argparse
import os
import sys

import yaml

from pirate import paths
from pirate.sequencer.guards import load_files
from pirate.supervisory import planner
from pirate.world import network

SETTINGS_FILE = os.path.join(paths.CONFIG_DIR, 'supervisory.yaml')


def load_settings(path=SETTINGS_FILE):
    """The planner's settings and the Drive limit of one goal (mm)."""
    with open(path) as stream:
        settings = yaml.safe_load(stream)
    return settings, float(load_files()[1]['drive']['max_distance'])


def main(argv=None):
    parser = argparse.ArgumentParser(prog='plan_mission', description=__doc__.split('\n')[0])
    parser.add_argument('map', help='world file, or its name in config/worlds/')
    parser.add_argument('points', nargs='+', help='FROM TO [...]: point names, visited in order')
    parser.add_argument('--speed', type=float, default=None, help='mm/s (default: config/supervisory.yaml)')
    parser.add_argument('--no-home', action='store_true', help='end clamped instead of homing')
    args = parser.parse_args(argv)
    try:
        settings, max_drive_mm = load_settings()
        pipe_map = network.load(network.world_path(args.map))
        route_plan = planner.plan(pipe_map, args.points, settings, max_drive_mm, args.speed, not args.no_home)
    except (network.WorldError, planner.PlanError) as refused:
        print('plan_mission: %s' % refused, file=sys.stderr)
        return 2
    print('\n'.join(planner.format_plan(route_plan)))
    try:
        planner.check_runnable(route_plan)
    except planner.PlanError as not_yet:
        print('plan_mission: this plan cannot run yet (run_mission refuses it before anything moves): %s'
              % not_yet, file=sys.stderr)
    return 0
