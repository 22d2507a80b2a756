"""The simulated robot: the physics twin (twin*.py, boards.py) and its ROS
edge (robot_node.py); fake_robot.py is a fitted fast fake that only unit tests
build, not physics. The in-process harness is in pirate.testing."""
