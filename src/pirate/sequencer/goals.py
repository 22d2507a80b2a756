"""The goal vocabulary shared by every client: PAB names, options, fields.

Missions (pirate.supervisory.mission) and the panel map
(pirate.panel.config) both name goals in words and are checked against
these tables before anything is sent (SPEC 6, report Table 4.4). Pure.
"""
from pirate.sequencer.pabs import PABS, codes

#: PAB name -> goal code (Pirate.action's name constants).
CODES = {row[0]: code for code, row in PABS.items()}
CODE_NAMES = {code: name for name, code in CODES.items()}
#: Pirate.action's option constants.
OPTION_NAMES = codes.OPTION_NAMES
OPTIONS = {name: code for code, name in OPTION_NAMES.items()}
#: The options each PAB needs (one of them); the others take none.
PAB_OPTIONS = {'CLAMP_SIDEWAYS': ('LEFT', 'RIGHT'), 'T_JOINT': ('LEFT', 'RIGHT', 'STRAIGHT'),
               'MITRE_BEND': ('LEFT', 'RIGHT', 'UP', 'DOWN')}
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
