"""Test rigs: what tests and bench/ build the robot stack from, never the
product itself. The in-process harness (the Pirate Server on the physics
twin), its start poses, the report's Chapter 6 runs, the twin's ground
truth, the executive's in-process robot and the firmware-in-the-loop robot.

Every layer may be imported from here; nothing outside this package and the
tests imports it.
"""
