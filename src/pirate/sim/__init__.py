"""The simulated robot: a physics model (model.py) and its ROS edge (node.py)."""
