"""A second publisher on the command topics is detected (pure part).

The ROS wiring (manager_node._on_command: cancel, hold, STOP, /diagnostics)
is covered by test/rostest/fault_rogue_writer.test.
"""
from pirate.robot.writers import OneWriter

SETPOINT = '/pirate/setpoint_array'


def test_the_owner_is_no_rogue():
    writers = OneWriter('/pirate_manager')
    assert writers.heard(SETPOINT, '/pirate_manager', 1.0) is None
    assert writers.refusal(1.0) is None


def test_a_rogue_is_reported_once_and_refuses_goals_while_it_writes():
    writers = OneWriter('/pirate_manager', refuse_s=2.0)
    report = writers.heard(SETPOINT, '/rostopic_123', 1.0)
    assert '/rostopic_123' in report and SETPOINT in report
    assert writers.heard(SETPOINT, '/rostopic_123', 1.02) is None      # 50 Hz: once
    assert '/rostopic_123' in writers.refusal(2.5)
    assert writers.refusal(3.1) is None                                 # silent for 2 s
    assert writers.heard('/pirate/control_array', '/rostopic_123', 4.0)  # another topic: reported
