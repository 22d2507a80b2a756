"""Visualisation of PIRATE: URDF generator, RViz helper node, run plots."""
