"""The simulated robot: the physics twin (twin*.py, boards.py), its ROS edge
(node.py) and in-process harness (harness.py); fake_robot.py is a fitted
fast fake that only unit tests build, not physics."""
