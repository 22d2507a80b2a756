"""The goal codes of Pirate.action, for the pure core (no message import).

``name`` codes (SPEC 6) and ``option`` codes; a unit test checks they match
the generated message.
"""
CLAMP_STRAIGHT, CLAMP_SIDEWAYS, T_JOINT, MITRE_BEND, DRIVE, HOME = range(6)
NONE, LEFT, RIGHT, STRAIGHT, UP, DOWN = range(6)
#: Option code -> its name in Pirate.action.
OPTION_NAMES = {NONE: 'NONE', LEFT: 'LEFT', RIGHT: 'RIGHT', STRAIGHT: 'STRAIGHT', UP: 'UP', DOWN: 'DOWN'}
