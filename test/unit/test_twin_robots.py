"""bench/twin_robots: which drawn constants a sweep's outcomes follow."""
import os
from importlib.machinery import SourceFileLoader

from pirate.testing import drawn_robots

BENCH = SourceFileLoader('twin_robots', os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..',
                                                     'bench', 'twin_robots')).load_module()


def test_ranks_share_ties_and_spearman_reads_order_only():
    assert BENCH.ranks([3.0, 1.0, 3.0, 2.0]) == [3.5, 1.0, 3.5, 2.0]
    assert BENCH.spearman([1, 2, 3, 4], [10, 20, 30, 1000]) == 1.0
    assert BENCH.spearman([1, 2, 3, 4], [4, 3, 2, 1]) == -1.0
    assert BENCH.spearman([1, 2, 3], [5, 5, 5]) == 0.0


def test_success_counts_the_runs_of_drawn_robots_only():
    def record(robot, outcome):
        return {'params': {'robot': robot} if robot else {}, 'outcome': outcome}
    found = [record(1, 'succeeded'), record(1, 'aborted'), record(1, 'refused'), record(2, 'pose failed'),
             record(2, 'FALSE success'), record(None, 'succeeded')]
    assert BENCH.success_by_robot(found) == {1: (1, 2), 2: (0, 1)}


def test_the_constant_the_outcomes_follow_comes_first_with_its_halves():
    seed = 3
    friction = {n: drawn_robots.constants(seed, n)[0]['friction.wheel'] for n in range(1, 9)}
    order = sorted(friction, key=friction.get)
    rates = {n: (order.index(n), 8) for n in friction}         # success grows with the wheels' friction
    lines = BENCH.sensitivity(seed, rates)
    assert lines[0].startswith('8 robots')
    first = lines[2].split()
    assert first[:2] == ['friction.wheel', '+1.00'] and first[2:5] == ['0.5', 'to', '1.2']
    low = [rates[n] for n in friction if friction[n] < 0.85]
    assert lines[2].split('|')[0].endswith('%3.0f%% of %d ' % (100.0 * sum(d for d, _ in low) / (8 * len(low)),
                                                               8 * len(low)))
