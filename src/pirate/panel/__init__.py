"""Operator panel: channel map, MIDI device handling, virtual panel.

The modules here import no ROS (except ``mapper_ros`` and the ``*_node``
modules, which are the ROS edges) and pygame only where a module says so,
so the logic is unit-testable without a master or a MIDI device.
"""
