"""A PAB's typical duration for the operator's time left (pirate.supervisory.durations)."""
import pytest

from pirate.supervisory import durations
from pirate.supervisory.plan_cli import load_settings

TYPICAL = load_settings()[0]['typical_s']


@pytest.mark.parametrize('pab, distance_mm, speed_mm_s, expected_s', [
    ('CLAMP_STRAIGHT', 0.0, 0.0, TYPICAL['CLAMP_STRAIGHT']),
    ('DRIVE', 1500.0, 150.0, TYPICAL['DRIVE'] + 10.0),
    ('DRIVE', -300.0, 100.0, TYPICAL['DRIVE'] + 3.0),      # backwards takes as long
    ('DRIVE', 300.0, 0.0, TYPICAL['DRIVE']),               # no speed: no drive time known
    ('T_JOINT', 700.0, 0.0, TYPICAL['T_JOINT']),           # a search distance is no drive
    ('NOT_A_PAB', 0.0, 0.0, 0.0),
])
def test_a_pab_takes_its_typical_time_and_a_drive_its_distance_over_its_speed(
        pab, distance_mm, speed_mm_s, expected_s):
    assert durations.typical_s(pab, distance_mm, speed_mm_s, TYPICAL) == pytest.approx(expected_s)


def test_every_pab_has_a_typical_duration():
    from pirate.sequencer.goals import CODES
    assert set(CODES) <= set(TYPICAL)
