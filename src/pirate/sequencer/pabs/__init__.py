"""The PABs the Pirate Server can run, one table row each.

Adding a PAB: write its class (a :class:`pirate.sequencer.pabs.base.Pab`) and add a
row here. The codes (:mod:`pirate.sequencer.pabs.codes`) are the goal's
``name`` constants of Pirate.action (SPEC 6).
"""
from pirate.sequencer.pabs.clamp import Clamp
from pirate.sequencer.pabs.codes import CLAMP_STRAIGHT, CLAMP_SIDEWAYS, T_JOINT, MITRE_BEND, DRIVE, HOME
from pirate.sequencer.pabs.drive import Drive
from pirate.sequencer.pabs.home import Home
from pirate.sequencer.pabs.junction import TakeJunction

#: goal code -> (name, PAB class or None when not built yet)
PABS = {
    CLAMP_STRAIGHT: ('CLAMP_STRAIGHT', Clamp),
    CLAMP_SIDEWAYS: ('CLAMP_SIDEWAYS', Clamp),       # the same machine, target by side
    T_JOINT: ('T_JOINT', TakeJunction),
    MITRE_BEND: ('MITRE_BEND', TakeJunction),     # the same machine, by junction kind
    DRIVE: ('DRIVE', Drive),
    HOME: ('HOME', Home),
}
