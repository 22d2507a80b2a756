"""The operator launch's arguments, checked before anything starts.

``operator.launch`` runs :func:`main` as a parameter command, so roslaunch
reads it while it parses the file: a bad value stops roslaunch (exit 1)
with the argument named on stderr, and a wrong world name lists the worlds
there are. Pure: no ROS; arguments come as ``name:=value`` words.
"""
import os
import sys

from pirate.world import network

#: The values an argument may take, where they are few.
CHOICES = {
    'robot': ('sim', 'real'),
    'panel': ('virtual', 'midi', 'none'),
    'pipe_diameter': ('90', '110'),     # the diameters with guards (config/guards_*.yaml)
}
#: The arguments that are true or false.
FLAGS = ('rviz', 'record')
NO_PANEL = ('no operator panel (panel:=none): Play, Stop, confirm, pause and resume of a mission have no '
            'buttons; publish pirate/MidiInput on /ram/input/midi yourself, or start panel.launch')


def worlds():
    """The names of the worlds under config/worlds/."""
    return sorted(name[:-len('.yaml')] for name in os.listdir(network.WORLDS_DIR) if name.endswith('.yaml'))


def parse(words):
    """{name: value} from ``name:=value`` words; ValueError names a word that is not one."""
    args = {}
    for word in words:
        name, sep, value = word.partition(':=')
        if not sep or not name:
            raise ValueError('%r: name:=value is needed' % word)
        args[name] = value
    return args


def problems(args):
    """Every bad argument in ``args``, each a sentence naming it; [] when all are good."""
    found = []
    for name, allowed in sorted(CHOICES.items()):
        if name in args and args[name] not in allowed:
            found.append('%s:=%s: use %s' % (name, args[name], ' or '.join(allowed)))
    for name in FLAGS:
        if name in args and args[name].lower() not in ('true', 'false'):
            found.append('%s:=%s: true or false' % (name, args[name]))
    found.extend(_rate_problems(args))
    found.extend(_world_problems(args))
    return found


def _rate_problems(args):
    if 'rate' not in args:
        return []
    try:
        rate = float(args['rate'])
    except ValueError:
        return ['rate:=%s: a real-time factor above 0 is needed (a number, e.g. rate:=2)' % args['rate']]
    if not rate > 0:
        return ['rate:=%s: a real-time factor above 0 is needed' % args['rate']]
    if rate != 1 and args.get('robot') == 'real':
        return ['rate:=%s: the real robot runs in real time (rate:=1)' % args['rate']]
    return []


def _world_problems(args):
    """The world must exist, read well and start in a pipe of ``pipe_diameter``."""
    if args.get('robot', 'sim') != 'sim' or 'world' not in args:
        return []
    path = network.world_path(args['world'])
    if not os.path.exists(path):
        return ['world:=%s: no such world; the worlds there are: %s (or a path to a world file)'
                % (args['world'], ', '.join(worlds()))]
    try:
        world = network.load(path)
    except network.WorldError as bad:
        return ['world:=%s: %s' % (args['world'], bad)]
    start_mm = round(world.diameter_at(world.start_m) * 1000.0)
    if args.get('pipe_diameter') in CHOICES['pipe_diameter'] and int(args['pipe_diameter']) != start_mm:
        return ['world:=%s starts in a %d mm pipe but pipe_diameter:=%s: give pipe_diameter:=%d'
                % (args['world'], start_mm, args['pipe_diameter'], start_mm)]
    return []


def warnings(args):
    """What the operator must know about a good set-up (a launch without a panel)."""
    return [NO_PANEL] if args.get('panel') == 'none' else []


def main(argv=None):
    """Check the words; problems to stderr and exit 1, else warnings to stderr and a summary to stdout."""
    try:
        args = parse(sys.argv[1:] if argv is None else argv)
    except ValueError as bad:
        sys.stderr.write('launch check: %s\n' % bad)
        return 1
    bad = problems(args)
    for line in bad:
        sys.stderr.write('launch argument: %s\n' % line)
    if bad:
        return 1
    for line in warnings(args):
        sys.stderr.write('WARNING: %s\n' % line)
    print(' '.join('%s:=%s' % item for item in sorted(args.items())))
    return 0
