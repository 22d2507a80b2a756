#!/usr/bin/env python3
"""Load for the trace rostest: keep one core busy until killed (roslaunch ends it).

Primitives can go missing from the feedback on a loaded machine; the trace
in the result must not. Pure CPU, no ROS traffic.
"""
import time

if __name__ == '__main__':
    end = time.monotonic() + 600.0      # a safety net if the launch forgets it
    while time.monotonic() < end:
        sum(i * i for i in range(10000))
