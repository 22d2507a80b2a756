"""PIRATE control stack: the pure-Python library behind the nodes.

Importing this package imports no ROS module; the ROS edges live in the
``*_node`` modules and in ``nodes/``.
"""
