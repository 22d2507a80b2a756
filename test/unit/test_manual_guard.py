"""Manual motion bounded (pirate.panel.manual_guard and the Mapper's side):
a motor the panel drives without progress is stopped within the configured
time, with the reason on the panel."""
import pytest

from pirate.panel import manual_guard
from pirate.panel.manual_guard import ManualGuard, WHEELS
from pirate.sequencer.guards import load_files

from pirate.panel.config import PAB

from test_mapper import PLAY, REWIND, SLIDER_BEND_I, SLIDER_DRIVE, STOP, Rig

SETTINGS = manual_guard.settings(load_files()[1])
ANGLES = dict(front_tilt=0.0, bend_i=0.3, bend_ii=-0.3, bend_iii=-0.3, bend_iv=0.3, rotation=0.0)
TICK_S = 0.1


def run(guard, seconds, driven, front_mm_s, rear_mm_s, bend_rad_s=0.0):
    """Drive ``guard`` at 10 Hz for ``seconds``; the first stall (s, motor, why), or None."""
    for tick in range(int(round(seconds / TICK_S)) + 1):
        now = tick * TICK_S
        angles = dict(ANGLES, bend_i=ANGLES['bend_i'] + bend_rad_s * now)
        stalled = guard.update(now, driven, angles, {'front': front_mm_s * now, 'rear': rear_mm_s * now})
        if stalled:
            return (now,) + stalled[0]
    return None


@pytest.mark.parametrize('case,driven,front,rear,bend,stops', [
    ('the robot drives', [WHEELS], 40.0, 40.0, 0.0, False),
    ('slow but moving', [WHEELS], 3.0, 3.0, 0.0, False),
    ('a stalled motor', [WHEELS], 0.0, 0.0, 0.0, True),
    ('the front wheels spin at an end cap', [WHEELS], 68.0, 2.0, 0.0, True),     # 40 868 vs 1 304 mm in 10 min
    ('a wheel off the wall', [WHEELS], 0.0, 40.0, 0.0, True),
    ('a bend moving', ['bend_i'], 0.0, 0.0, 0.05, False),
    ('a bend at its stop', ['bend_i'], 0.0, 0.0, 0.0, True),
    ('nothing driven', [], 0.0, 0.0, 0.0, False),
])
def test_a_motor_driven_without_progress_stops_within_the_set_time(case, driven, front, rear, bend, stops):
    found = run(ManualGuard(SETTINGS), 60.0, driven, front, rear, bend)
    if not stops:
        assert found is None, case
        return
    now, motor, why = found
    assert motor == driven[0]
    assert SETTINGS.no_progress_s <= now <= SETTINGS.no_progress_s + 2 * TICK_S, case
    assert ('without the robot advancing' if motor == WHEELS else 'without moving') in why


def test_a_stall_is_said_once_and_watched_anew_when_driven_again():
    guard = ManualGuard(SETTINGS)
    stops = [guard.update(t * TICK_S, [WHEELS], ANGLES, {'front': 0.0, 'rear': 0.0}) for t in range(100)]
    assert sum(1 for s in stops if s) == 1
    guard.update(10.0, [], ANGLES, {'front': 0.0, 'rear': 0.0})
    assert run(guard, 10.0, [WHEELS], 0.0, 0.0)[1] == WHEELS


def test_the_wheels_stopped_by_the_guard_and_the_panel_told():
    rig = Rig()
    rig.press(PLAY)
    rig.mapper.handle(SLIDER_DRIVE, 127)
    assert rig.mapper.manually_driven() == [WHEELS]
    why = 'wheels driven 3.0 s without the robot advancing'
    rig.mapper.stop_stalled(WHEELS, why)
    assert rig.setpoint.get(WHEELS) == 0
    assert rig.logs[-1] == why
    assert rig.mapper.manually_driven() == []


def test_a_pwm_bend_driven_by_its_slider_is_watched():
    rig = Rig()
    rig.press(PLAY)
    rig.mapper.handle(SLIDER_BEND_I, 127)
    assert rig.control.mode_of('bend_i') == 'pwm' and rig.mapper.manually_driven() == ['bend_i']


def test_nothing_is_watched_stopped_or_in_pab_mode():
    rig = Rig()
    rig.press(PLAY)
    rig.mapper.handle(SLIDER_DRIVE, 127)
    rig.press(STOP)
    assert rig.mapper.manually_driven() == []
    rig.press(REWIND)
    rig.press(PLAY)
    assert rig.mapper.operation_mode == PAB and rig.mapper.manually_driven() == []
