"""The robot as the laptop sees it: its tables, units, limits and the command arrays.

Pure: imports no ROS module."""
