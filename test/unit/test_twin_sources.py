"""Every constant of config/twin.yaml has its source (config/twin_sources.yaml).

- every constant has an entry and every entry names a constant;
- an estimate has a range [low, high] holding its value (one per element
  of a list value);
- a report source names a section, a fitted one its experiment and a bench
  with the option that refits it;
- and each of those checks fails on an entry that breaks it.
"""
import pytest

from pirate.sim import twin_sources

CONFIG = {'bend': {'stall_nm': 1.2, 'no_load_rad_s': 0.311, 'gear_ratio': 87},
          'front_tilt': {'range_rad': [-0.1, 1.2]}}
FIT = {'kind': 'fitted', 'source': 'joint speed', 'experiment': 'Table 6.1, simple clamp straight',
       'bench': 'bench/sim_twin_calibration --fit'}


def _sources(**changes):
    """Good sources for CONFIG with ``changes`` ({dotted name with '__' for '.': entry or None})."""
    sources = {'bend.stall_nm': {'kind': 'estimate', 'source': 'motor', 'range': [0.5, 3.0]},
               'bend.no_load_rad_s': dict(FIT),
               'bend.gear_ratio': {'kind': 'report', 'section': '2.4.3.1', 'page': 14, 'source': 'worm'},
               'front_tilt.range_rad': {'kind': 'estimate', 'source': 'stops', 'range': [[-0.2, 0.0], [1.0, 1.4]]}}
    for key, entry in changes.items():
        name = key.replace('__', '.')
        if entry is None:
            del sources[name]
        else:
            sources[name] = entry
    return sources


def test_every_constant_of_the_twin_has_its_source():
    config, sources = twin_sources.load()
    assert twin_sources.problems(config, sources) == []


def test_the_good_example_has_no_problem():
    assert twin_sources.problems(CONFIG, _sources()) == []


@pytest.mark.parametrize('changes, problem', [
    ({'bend__stall_nm': None}, 'bend.stall_nm: no entry'),
    ({'bend__stall_mnm': {'kind': 'choice', 'source': 'x'}}, 'bend.stall_mnm: an entry for no constant'),
    ({'bend__stall_nm': {'kind': 'estimate', 'source': 'motor'}}, 'bend.stall_nm: an estimate needs a range'),
    ({'bend__stall_nm': {'kind': 'estimate', 'source': 'motor', 'range': [1.5, 3.0]}},
     'bend.stall_nm: range [1.5, 3] does not hold the value 1.2'),
    ({'bend__stall_nm': {'kind': 'estimate', 'source': 'motor', 'range': [3.0, 0.5]}},
     'bend.stall_nm: range [3, 0.5]: low above high'),
    ({'front_tilt__range_rad': {'kind': 'estimate', 'source': 'stops', 'range': [-0.2, 1.4]}},
     'front_tilt.range_rad: an estimate of 2 values needs one [low, high] per value'),
    ({'front_tilt__range_rad': {'kind': 'estimate', 'source': 'stops', 'range': [[-0.2, 0.0], [1.3, 1.4]]}},
     'front_tilt.range_rad: range [1.3, 1.4] does not hold the value 1.2'),
    ({'bend__gear_ratio': {'kind': 'report', 'source': 'worm'}}, 'bend.gear_ratio: a report source names no section'),
    ({'bend__gear_ratio': {'kind': 'report', 'section': 'p. 14', 'source': 'worm'}},
     'bend.gear_ratio: a report source names no section'),
    ({'bend__no_load_rad_s': dict(FIT, experiment=None)}, 'bend.no_load_rad_s: a fitted constant names no experiment'),
    ({'bend__no_load_rad_s': dict(FIT, bench='bench/no_such_bench --fit')},
     "bend.no_load_rad_s: its bench 'bench/no_such_bench' does not exist"),
    ({'bend__no_load_rad_s': dict(FIT, bench='bench/sim_twin_calibration --refit')},
     "bend.no_load_rad_s: bench/sim_twin_calibration has no option '--refit'"),
    ({'bend__stall_nm': dict(FIT)}, 'bend.stall_nm: bench/sim_twin_calibration does not fit it'),
    ({'bend__stall_nm': {'kind': 'guess', 'source': 'motor'}}, "bend.stall_nm: kind 'guess' is none of"),
    ({'bend__stall_nm': {'kind': 'estimate', 'range': [0.5, 3.0]}}, 'bend.stall_nm: no source'),
    ({'bend__stall_nm': {'kind': 'estimate', 'source': 'motor', 'range': [0.5, 3.0], 'rnage': 1}},
     'bend.stall_nm: unknown field rnage'),
    ({'bend__stall_nm': {'kind': 'choice', 'source': 'motor', 'row': 'no-such-row'}},
     'bend.stall_nm: no row no-such-row in doc/measurements.md'),
])
def test_a_broken_entry_is_named_with_what_is_wrong(changes, problem):
    found = twin_sources.problems(CONFIG, _sources(**changes))
    assert len(found) == 1 and found[0].startswith(problem), found


def test_the_table_has_a_row_per_constant_with_its_kind_and_range():
    table = twin_sources.markdown(CONFIG, _sources())
    assert '| `bend.stall_nm` | 1.2 | estimate | motor | 0.5 to 3 |' in table
    assert '| `front_tilt.range_rad` | [-0.1, 1.2] | estimate | stops | -0.2 to 0, 1 to 1.4 |' in table
    assert '| `bend.gear_ratio` | 87 | report | 2.4.3.1, p. 14: worm |  |' in table
    assert 'refitted by `bench/sim_twin_calibration --fit`' in table
    assert table.endswith('4 constants: 1 report, 1 fitted, 2 estimate.')


def test_a_drawn_robot_has_every_ranged_constant_inside_its_range_and_the_rest_nominal():
    config, sources = twin_sources.load()
    robot, changes = twin_sources.drawn(7, config, sources)
    ranged = {c.name: c for c in twin_sources.constants(config, sources) if c.range is not None}
    assert set(changes) == set(ranged)
    for name, constant in ranged.items():
        section, key = name.split('.')
        value = robot[section][key]
        pairs = constant.range if isinstance(constant.value, list) else [constant.range]
        for element, (low, high) in zip(value if isinstance(value, list) else [value], pairs):
            assert low <= element <= high, name
        assert isinstance(value, type(constant.value)), name
    for constant in twin_sources.constants(config, sources):
        if constant.range is None:
            section, key = constant.name.split('.')
            assert robot[section][key] == constant.value, constant.name
    assert twin_sources.drawn(7, config, sources)[0] == robot, 'robot 7 is drawn from its seed alone'
    assert twin_sources.drawn(8, config, sources)[0] != robot
    assert config == twin_sources.load()[0], 'the nominal constants are untouched'
