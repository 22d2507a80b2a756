"""bench/report_test_pipe: the report's bore from Table 6.5 and eq 2.1."""
import math
import os
from importlib.machinery import SourceFileLoader

import pytest

BENCH = SourceFileLoader('report_test_pipe', os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..',
                                                          'bench', 'report_test_pipe')).load_module()
GEOMETRY = {'module_length_m': 0.09, 'wheel_diameter_m': 0.046}


def test_a_clamp_at_the_apex_angle_of_a_bore_gives_that_bore_back():
    assert BENCH.bore_mm(math.asin((0.090 - 0.046) / 0.09), GEOMETRY) == pytest.approx(90.0)
    assert BENCH.bore_mm(math.asin((0.083 - 0.046) / 0.09), GEOMETRY) == pytest.approx(83.0)


def test_table_6_5_puts_the_report_in_a_90_mm_sdr_26_pipe():
    bores = [bore for _, bore in BENCH.implied_bores(GEOMETRY)]
    assert len(bores) == 4 and 81.5 < min(bores) and max(bores) < 84.5
    assert [sdr for sdr, _, _ in BENCH.matching_pipes(sum(bores) / 4, 1.0)] == [26]
    assert BENCH.matching_pipes(90.0, 1.0) == [], 'no standard 90 mm pipe has a 90 mm bore'
