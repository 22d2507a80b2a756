"""The goal vocabulary shared by every client: PAB names, options, fields.

Missions (pirate.supervisory.mission) and the panel map
(pirate.panel.config) both name goals in words and are checked against
these tables before anything is sent (SPEC 6, report Table 4.4). Pure.
"""
from pirate.sequencer.junctions import STRAIGHT_CLAMP, label
from pirate.sequencer.pabs import PABS, codes
from pirate.sequencer.pabs.junction import JUNCTIONS, straight_sideways_problem

#: PAB name -> goal code (Pirate.action's name constants).
CODES = {row[0]: code for code, row in PABS.items()}
CODE_NAMES = {code: name for name, code in CODES.items()}
#: Pirate.action's option constants.
OPTION_NAMES = codes.OPTION_NAMES
OPTIONS = {name: code for code, name in OPTION_NAMES.items()}
#: The options each PAB needs (one of them); the others take none.
PAB_OPTIONS = {'CLAMP_SIDEWAYS': ('LEFT', 'RIGHT'), 'T_JOINT': ('LEFT', 'RIGHT', 'STRAIGHT'),
               'MITRE_BEND': ('LEFT', 'RIGHT', 'UP', 'DOWN')}
#: The option a PAB that takes none is sent with.
NO_OPTION = 'NONE'
#: Goal fields a PAB takes besides its pipe diameter and option.
PAB_FIELDS = {'DRIVE': ('distance', 'speed')}


def built(pab, option=None, rear_first=False):
    """True when the Pirate Server can run PAB ``pab`` (a name of :data:`CODES`),
    with ``option`` (a name of :data:`OPTIONS`) when one is given, backwards
    (a junction searched rear first) when ``rear_first``."""
    pab_class = PABS[CODES[pab]][1]
    if pab_class is None:
        return False
    if option is None and not rear_first:
        return True
    return pab_class.takes(CODES[pab], OPTIONS.get(option), rear_first)


def start_clamps(pab, option, guards=None):
    """Names (:func:`pirate.sequencer.junctions.label`) of the clamps the
    junction PAB ``pab`` (goal name, 'T_JOINT' or 'MITRE_BEND') declares it
    starts ``option`` (an option name, e.g. 'STRAIGHT') from; () for an
    option it has none for. With ``guards`` (a diameter's,
    pirate.sequencer.guards), straight on from a sideways clamp only where
    they take it (junction.straight_sideways_problem)."""
    clamps = JUNCTIONS[CODES[pab]][3].get(OPTIONS.get(option), (None, ()))[1]
    if option != 'STRAIGHT' or guards is None:
        return clamps
    if straight_sideways_problem(guards, float('inf')):
        return tuple(clamp for clamp in clamps if clamp == label(STRAIGHT_CLAMP))
    return clamps


def option_refusal(name, option):
    """Why PAB code ``name`` does not take option code ``option`` (codes of
    Pirate.action), naming the options it takes; None when it takes it (or
    needs one and got none: the PAB itself says which), and for a code that
    is no PAB of Pirate.action."""
    if name not in CODE_NAMES:
        return None
    pab = CODE_NAMES[name]
    takes = PAB_OPTIONS.get(pab, (NO_OPTION,))
    if option in OPTION_NAMES and (OPTION_NAMES[option] in takes or OPTION_NAMES[option] == NO_OPTION):
        return None
    given = ('%d %s' % (option, OPTION_NAMES[option]) if option in OPTION_NAMES
             else '%d (no option of Pirate.action)' % option)
    return '%s takes option %s, not %s' % (pab, ' or '.join('%d %s' % (OPTIONS[o], o) for o in takes), given)
