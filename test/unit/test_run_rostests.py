"""scripts/run_rostests judges each rostest by its summary, with a fake rostest.

A fake ``rostest`` on PATH prints what the real one prints with --text, so
the verdict logic is tested without starting a master.
"""
import os
import stat
import subprocess

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))

SUCCESS = """SUMMARY:
\x1b[32m * RESULT: SUCCESS\x1b[0m
 * TESTS: 3
 * ERRORS: 0 []
 * FAILURES: 0 []
"""
FAILURE = """SUMMARY:
 * RESULT: FAIL
 * TESTS: 3
 * ERRORS: 0 []
 * FAILURES: 1 [test_2]
"""
ERROR = """SUMMARY:
 * RESULT: FAIL
 * TESTS: 3
 * ERRORS: 1 [test_1]
 * FAILURES: 0 []
"""


def run_with_fake_rostest(tmp_path, output, exit_code):
    fake = tmp_path / 'rostest'
    fake.write_text('#!/bin/bash\ncat <<"OUT"\n%sOUT\nexit %d\n' % (output, exit_code))
    fake.chmod(fake.stat().st_mode | stat.S_IXUSR)
    env = dict(os.environ, PATH='%s:/usr/bin:/bin' % tmp_path)
    # one existing rostest file, so exactly one verdict is printed
    return subprocess.run(['bash', 'scripts/run_rostests', 'sim_time'], cwd=ROOT, env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=30)


def test_a_passing_rostest_passes(tmp_path):
    result = run_with_fake_rostest(tmp_path, SUCCESS, 0)
    assert 'PASS test/rostest/sim_time.test' in result.stdout
    assert result.returncode == 0


@pytest.mark.parametrize('output,exit_code', [(FAILURE, 1), (ERROR, 1), (FAILURE, 0),
                                              (SUCCESS, 1), ('', 0)])
def test_a_failing_or_broken_rostest_fails(tmp_path, output, exit_code):
    result = run_with_fake_rostest(tmp_path, output, exit_code)
    assert 'FAIL test/rostest/sim_time.test' in result.stdout
    assert result.returncode != 0
