"""Guard tables (SPEC 7, report Tables 5.2 and 5.3) as loaded from config/.

The expected values below are transcribed from SPEC 7 independently of the
YAML files, so a typo in either shows up as a failure.
"""
import math

import pytest

from pirate.sequencer.guards import GuardBook, Guards, NoGuards, load_files

# (primitive, part) -> ((outer joint, setpoint, guard), (inner joint, setpoint, guard))
# Table 5.2 (SPEC 7), 90 mm and 110 mm columns.
TABLE_5_2 = {
    90: {
        ('clamp', 'front'): (('bend_i', 256, -0.77), ('bend_ii', -256, 0.35)),
        ('clamp', 'rear'): (('bend_iv', 256, -0.77), ('bend_iii', -256, 0.35)),
        ('unclamp', 'rear'): (('bend_iv', -100, -0.15), ('bend_iii', 150, 0.07)),
        ('unclamp', 'front'): (('bend_i', -100, -0.2), ('bend_ii', 150, 0.03)),
        ('unclamp_partial', 'front'): (('bend_i', -100, -0.48), ('bend_ii', 150, 0.29)),
        ('unclamp_partial', 'rear'): (('bend_iv', -100, -0.48), ('bend_iii', 150, 0.29)),
    },
    110: {
        ('clamp', 'front'): (('bend_i', 256, -1.25), ('bend_ii', -256, 0.65)),
        ('clamp', 'rear'): (('bend_iv', 256, -1.25), ('bend_iii', -256, 0.65)),
        ('unclamp', 'rear'): (('bend_iv', -100, -0.15), ('bend_iii', 150, 0.07)),
        ('unclamp', 'front'): (('bend_i', -100, -0.2), ('bend_ii', 150, 0.03)),
        ('unclamp_partial', 'front'): (('bend_i', -100, -0.9), ('bend_ii', 150, 0.45)),
        ('unclamp_partial', 'rear'): (('bend_iv', -100, -0.9), ('bend_iii', 150, 0.45)),
    },
}
# Table 5.3 (SPEC 7): custom clamps, 90 mm only.
TABLE_5_3_CLAMPS = {
    ('clamp_front_custom_first', 'front'): (('bend_i', 256, -0.69), ('bend_ii', -256, 0.30)),
    ('clamp_front_custom', 'front'): (('bend_i', 256, -0.72), ('bend_ii', -256, 0.30)),
    ('clamp_rear_custom', 'rear'): (('bend_iv', 256, -0.68), ('bend_iii', -256, 0.33)),
}
# Table 5.3: move front (PWM 32) guards on the front module angle.
TABLE_5_3_MOVES = {
    90: {'move_front': (32, 0.4), 'move_front_first': (32, 0.105), 'move_front_later': (32, 0.3)},
    110: {'move_front': (32, 0.7)},
}
ALIGN_TOLERANCE = 0.0425
REGIONS = {'straight': (1.52, 1.62), 'nominal': (1.4, 1.74)}   # Table 5.4


@pytest.fixture(scope='module')
def book():
    return GuardBook(*load_files())


def _check_pair(pair, expected):
    (outer_joint, outer_sp, outer_guard), (inner_joint, inner_sp, inner_guard) = expected
    assert (pair.outer.joint, pair.outer.setpoint) == (outer_joint, outer_sp)
    assert pair.outer.guard == pytest.approx(outer_guard)
    assert (pair.inner.joint, pair.inner.setpoint) == (inner_joint, inner_sp)
    assert pair.inner.guard == pytest.approx(inner_guard)


def test_config_loads_both_diameters(book):
    assert book.diameters() == [90, 110]
    for mm in (90, 110):
        assert book.for_diameter(mm).pipe_diameter == mm


@pytest.mark.parametrize('mm', [90, 110])
def test_table_5_2(book, mm):
    guards = book.for_diameter(mm)
    for (kind, part), expected in TABLE_5_2[mm].items():
        _check_pair(guards.pair(kind, part), expected)


def test_table_5_3_custom_clamps_90(book):
    guards = book.for_diameter(90)
    for (kind, part), expected in TABLE_5_3_CLAMPS.items():
        assert guards.has(kind)
        _check_pair(guards.pair(kind, part), expected)


@pytest.mark.parametrize('mm', [90, 110])
def test_table_5_3_move_front(book, mm):
    guards = book.for_diameter(mm)
    for kind, (setpoint, guard) in TABLE_5_3_MOVES[mm].items():
        move = guards.move(kind)
        assert move.setpoint == setpoint
        assert move.guard == pytest.approx(guard)


@pytest.mark.parametrize('mm', [90, 110])
def test_align_tolerance_and_regions(book, mm):
    guards = book.for_diameter(mm)
    assert guards.align_tolerance == pytest.approx(ALIGN_TOLERANCE)
    for name, region in REGIONS.items():
        assert guards.region(name) == pytest.approx(region)
    assert guards.primitive_timeout == pytest.approx(15.0)   # report 5.9


def test_full_unclamp_name_maps_to_the_part(book):
    guards = book.for_diameter(90)
    assert guards.pair('unclamp', 'front').kind == 'unclamp_front'
    assert guards.pair('unclamp', 'rear').kind == 'unclamp_rear'


@pytest.mark.parametrize('mm', [100, 0, 160])
def test_unknown_diameter_has_no_guards(book, mm):
    with pytest.raises(NoGuards) as info:
        book.for_diameter(mm)
    text = str(info.value)
    assert str(mm) in text and '90' in text and '110' in text


@pytest.mark.parametrize('kind', ['clamp_front_custom_first', 'clamp_front_custom', 'clamp_rear_custom'])
def test_a_missing_custom_clamp_row_is_refused_with_its_name(book, kind):
    # 110 mm has derived custom rows (test_clamp_sideways_guards.py); a
    # table without one still names what is missing.
    tables, common = load_files()
    table = {key: value for key, value in tables[110].items() if key != kind}
    part = 'rear' if 'rear' in kind else 'front'
    with pytest.raises(NoGuards) as info:
        Guards(table, common).pair(kind, part)
    assert kind in str(info.value) and '110' in str(info.value)
    assert book.for_diameter(110).has(kind)


@pytest.mark.parametrize('kind', ['move_front_first', 'move_front_later'])
def test_a_missing_move_row_is_refused(kind):
    tables, common = load_files()
    table = {key: value for key, value in tables[110].items() if key != kind}
    with pytest.raises(NoGuards):
        Guards(table, common).move(kind)


def test_unknown_common_setting_is_an_attribute_error(book):
    with pytest.raises(AttributeError):
        book.for_diameter(90).no_such_setting   # pylint: disable=expression-not-assigned


def test_book_from_param_server_layout():
    """The manager reads {param key: table}; keys are not the diameters."""
    tables, common = load_files()
    book = GuardBook({'pipe%d' % mm: t for mm, t in tables.items()}, common)
    assert book.diameters() == [90, 110]
    assert isinstance(book.for_diameter(110), Guards)


def test_no_guard_value_is_nan(book):
    for mm in book.diameters():
        guards = book.for_diameter(mm)
        for (kind, part) in TABLE_5_2[mm]:
            pair = guards.pair(kind, part)
            assert math.isfinite(pair.outer.guard) and math.isfinite(pair.inner.guard)
