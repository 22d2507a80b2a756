"""The run plot draws what the run holds: one marker per executed primitive,
the straight band, the guards of the primitives that ran. Synthetic data,
no bag; the PNG is kept in test-results/ to look at."""
import math
import os

import pytest
import yaml

from pirate.robot import tables
from pirate.viz import plot

RESULTS = os.path.join(os.path.dirname(__file__), '..', '..', 'test-results')
CONFIG = os.path.join(os.path.dirname(__file__), '..', '..', 'config')

#: A simple clamp straight as the report's Table 6.1 lists it.
SIMPLE = (('move front', 0.5), ('clamp rear', 3.0), ('clamp front', 6.5))


def _feedback():
    """Feedback at 10 Hz: each primitive repeated while it runs, gaps between."""
    rows = []
    for (name, start), end in zip(SIMPLE, [s for _, s in SIMPLE[1:]] + [10.0]):
        t = start
        while t < end - 0.3:
            rows.append((t, 'goal-1', name))
            t += 0.1
        rows.append((end - 0.2, 'goal-1', ''))
    return rows


def _run():
    times = [i * 0.1 for i in range(120)]
    positions = {j: [0.0] * len(times) for j in tables.JOINT_NAMES}
    positions['front_tilt'] = [min(0.45, max(0.0, 0.2 * (t - 0.5))) for t in times]
    positions['bend_iv'] = [-min(0.82, max(0.0, 0.4 * (t - 3.0))) for t in times]
    positions['bend_i'] = [-min(0.82, max(0.0, 0.4 * (t - 6.5))) for t in times]
    efforts = {j: [10.0 * math.sin(t) for t in times] for j in tables.JOINT_NAMES}
    orientation = [math.pi / 2 + 0.02 * math.sin(t) for t in times]
    return plot.Run(times, positions, efforts, orientation, plot.transitions(_feedback()))


def test_transitions_mark_each_primitive_once():
    assert plot.transitions(_feedback()) == [(0.5, 'move front'), (3.0, 'clamp rear'),
                                             (6.5, 'clamp front')]


def test_same_primitive_twice_is_marked_twice():
    rows = [(0, 'g', 'clamp front'), (1, 'g', 'clamp front'), (2, 'g', ''),
            (3, 'g', 'clamp front'), (4, 'h', 'clamp front')]
    assert plot.transitions(rows) == [(0, 'clamp front'), (3, 'clamp front'),
                                      (4, 'clamp front')]


def _guards_90():
    with open(os.path.join(CONFIG, 'guards_90.yaml')) as f:
        return yaml.safe_load(f)


def test_guard_lines_of_the_primitives_that_ran():
    table = _guards_90()
    lines = plot.guard_lines(table, ['move front', 'clamp rear', 'clamp front',
                                     'unclamp front partial', 'rotate'])
    clamp, partial = table['clamp'], table['unclamp_partial']
    assert lines == {
        'front_tilt': [('move front', table['move_front']['guard'])],
        'bend_iv': [('clamp rear', clamp['outer']['guard'])],
        'bend_iii': [('clamp rear', clamp['inner']['guard'])],
        'bend_i': [('clamp front', clamp['outer']['guard']),
                   ('unclamp front partial', partial['outer']['guard'])],
        'bend_ii': [('clamp front', clamp['inner']['guard']),
                    ('unclamp front partial', partial['inner']['guard'])]}


def test_custom_and_full_unclamp_rows():
    table = _guards_90()
    lines = plot.guard_lines(table, ['clamp rear custom', 'clamp front custom first',
                                     'unclamp rear', 'move front later'])
    assert lines['bend_iv'] == [('clamp rear custom', table['clamp_rear_custom']['outer']['guard']),
                                ('unclamp rear', table['unclamp_rear']['outer']['guard'])]
    assert lines['bend_i'] == [('clamp front custom first',
                                table['clamp_front_custom_first']['outer']['guard'])]
    assert lines['front_tilt'] == [('move front later', table['move_front_later']['guard'])]


def test_no_guard_lines_without_config_or_rows():
    assert plot.guard_lines(None, ['clamp front']) == {}
    assert plot.guard_lines(_guards_90(), ['rotate', 'align', 'no such primitive']) == {}


def test_plot_draws_the_run(tmp_path):
    os.makedirs(RESULTS, exist_ok=True)
    path = os.path.join(RESULTS, 'plot_synthetic_clamp_straight.png')
    if os.path.exists(path):
        os.remove(path)
    run = _run()
    guards = plot.guard_lines(_guards_90(), [p for _, p in run.markers])
    drawn, markers = plot.plot_run(run, path, guards, 'synthetic simple clamp straight')
    with open(path, 'rb') as f:
        assert f.read(8) == b'\x89PNG\r\n\x1a\n'
    assert [p for _, p in markers] == ['move front', 'clamp rear', 'clamp front']
    titles = [p.title for p in drawn]
    assert len(drawn) == 5 and titles[-1] == 'Bend efforts'
    rotation = drawn[2]
    assert [s[0] for s in rotation.series] == ['Rotation (25)', 'Orientation']
    assert rotation.series[1][2] == run.orientation
    assert rotation.bands == [(1.52, 1.62)]
    assert rotation.references[0][1] == pytest.approx(math.pi / 2)
    front = drawn[1]
    assert [s[0] for s in front.series] == ['Bend I (22)', 'Bend II (23)']
    assert front.series[0][2] == run.positions['bend_i']
    clamp = _guards_90()['clamp']
    assert sorted(v for _, v in front.guards) == sorted([clamp['outer']['guard'],
                                                         clamp['inner']['guard']])
    assert [s[0] for s in drawn[4].series] == ['Bend I (22)', 'Bend II (23)',
                                               'Bend III (26)', 'Bend IV (27)']


def test_mismatched_lengths_are_refused(tmp_path):
    run = _run()._replace(orientation=[1.57])
    with pytest.raises(ValueError, match='orientation'):
        plot.plot_run(run, str(tmp_path / 'x.png'))


# --- the plot tells the whole run ------------------------------------------

def test_labels_of_close_transitions_do_not_overlap():
    times = [0.0, 0.1, 0.2, 5.0, 5.05, 10.0]
    rows = plot.label_rows(times, span=10.0, gap=0.035)
    assert rows == [0, 1, 2, 0, 1, 0]
    for row in set(rows):
        on_row = [t for t, r in zip(times, rows) if r == row]
        assert all(b - a >= 0.35 for a, b in zip(on_row, on_row[1:]))


def test_drive_panel_and_events(tmp_path):
    run = _run()._replace(odometry=[t * 10.0 for t in _run().times], velocity=[10.0] * 120,
                          events=[(7.0, 'cancelled: Clamp Straight cancelled during clamping front')],
                          title='Clamp Straight - 90 mm pipe - cancelled - run.bag')
    drawn, _ = plot.plot_run(run, str(tmp_path / 'x.png'))
    assert drawn[-1].title.startswith('Drive') and [s[0] for s in drawn[-1].series] == [
        'Odometry [mm]', 'Wheel speed [mm/s]']
    with pytest.raises(ValueError, match='Odometry'):
        plot.panels(run._replace(odometry=[1.0]))


def test_a_long_mission_marks_its_pab_spans_not_each_primitive(tmp_path):
    """103 primitives stacked their labels over the plot: the PABs' spans read instead."""
    run = _run()
    markers = [(i * 0.1, 'clamp rear') for i in range(103)]
    spans = [(0.0, 4.0, 'CLAMP_STRAIGHT'), (4.0, 9.0, 'DRIVE'), (9.0, 11.9, 'HOME')]
    run = run._replace(markers=markers, spans=spans, title='Mission inspection_network_90: ' + 'long words ' * 30)
    os.makedirs(RESULTS, exist_ok=True)
    _, drawn_markers = plot.plot_run(run, os.path.join(RESULTS, 'plot_run_spans.png'), xlim=(0.0, 20.0))
    assert drawn_markers == []
    assert plot.pab_entries(spans) == [('P1', 0.0, 'CLAMP_STRAIGHT  4.0 s'), ('P2', 4.0, 'DRIVE  5.0 s'),
                                       ('P3', 9.0, 'HOME  2.9 s')]
    few = [(0.5, 'move front'), (3.0, 'clamp rear')]
    assert plot.marked(few, spans) == (few, [])          # a single PAB keeps its primitives
