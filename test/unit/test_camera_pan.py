"""The camera pan has no encoder: the state rebuilds its angle from the
arrays sent to board 20, as its drive would have moved it."""
import pytest

from pirate.robot import safety, tables, units
from pirate.state.assembler import StateAssembler
from pirate.state.camera_pan import PanEstimate

TOP_RAD_S, STOPS = 2.0, (-1.5, 1.5)
PAN = tables.element('camera_pan').index


def _arrays(mode, counts, command='play'):
    setpoints, modes = [0] * tables.SETPOINT_SIZE, [safety.MODE_CODES['pwm']] * tables.CONTROL_SIZE
    modes[tables.element('rear_module').index] = safety.COMMAND_CODES[command]
    modes[PAN] = safety.MODE_CODES.get(mode, safety.COMMAND_CODES.get(mode))
    setpoints[PAN] = counts
    return setpoints, modes


def test_a_position_setpoint_is_reached_at_the_drive_speed():
    pan = PanEstimate(TOP_RAD_S, STOPS)
    pan.command(*_arrays('position', units.rad_to_encoder(1.0)), now=10.0)
    assert pan.angle(10.25) == pytest.approx(0.5)
    assert pan.angle(11.0) == pytest.approx(1.0, abs=0.002)      # there, and held
    assert pan.angle(20.0) == pytest.approx(1.0, abs=0.002)


def test_pwm_turns_at_the_duty_share_of_the_speed_until_a_stop():
    pan = PanEstimate(TOP_RAD_S, STOPS)
    pan.command(*_arrays('pwm', -128), now=0.0)
    assert pan.angle(0.5) == pytest.approx(-0.5)
    assert pan.angle(5.0) == pytest.approx(-1.5)


def test_stopped_boards_or_a_single_stop_hold_the_pan():
    pan = PanEstimate(TOP_RAD_S, STOPS)
    pan.command(*_arrays('position', units.rad_to_encoder(1.0), command='stop'), now=0.0)
    assert pan.angle(3.0) == 0.0
    pan.command(*_arrays('position', units.rad_to_encoder(1.0)), now=3.0)
    pan.command(*_arrays('single_stop', units.rad_to_encoder(1.0)), now=3.2)
    assert pan.angle(9.0) == pytest.approx(0.4)


def test_the_state_reports_the_pan_it_sent_not_zero():
    assembler = StateAssembler()
    assembler.command(*_arrays('position', units.rad_to_encoder(0.8)), now=1.0)
    snap = assembler.snapshot(3.0)
    assert snap.position[snap.name.index('camera_pan')] == pytest.approx(0.8, abs=0.002)
