"""The PABs the Pirate Server can run, one table row each.

Adding a PAB: write its class (a :class:`pirate.sequencer.pabs.base.Pab`) and add a
row here. The codes are the goal's ``name`` constants of Pirate.action
(SPEC 6); a unit test checks they match the generated message.
"""
from pirate.sequencer.pabs.clamp import Clamp
from pirate.sequencer.pabs.drive import Drive
from pirate.sequencer.pabs.home import Home

CLAMP_STRAIGHT, CLAMP_SIDEWAYS, T_JOINT, MITRE_BEND, DRIVE, HOME = range(6)

#: goal code -> (name, PAB class or None when not built yet)
PABS = {
    CLAMP_STRAIGHT: ('CLAMP_STRAIGHT', Clamp),
    CLAMP_SIDEWAYS: ('CLAMP_SIDEWAYS', None),
    T_JOINT: ('T_JOINT', None),
    MITRE_BEND: ('MITRE_BEND', None),
    DRIVE: ('DRIVE', Drive),
    HOME: ('HOME', Home),
}
