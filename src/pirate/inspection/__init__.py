"""Inspection: findings marked during a job, stored as they happen, and the report.

Pure core (pirate.inspection.findings, .store, .frames, .mission_log,
.report) and its ROS edge (pirate.inspection.inspection_node). See
doc/inspection.md.
"""
