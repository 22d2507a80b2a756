"""The robot's cameras as ROS topics: the twin's (pirate.sim.twin_camera)
and the real robot's (a V4L2 device), with the same topics and frames."""
