"""The inspection report as a person sees it: opened in headless Chromium
(Debian's ``chromium``), it shows every finding, the dig list in order and
the map; bad runs get clear errors."""
import os
import re
import shutil
import subprocess

import pytest
from PIL import Image

from pirate.inspection import report, store

import inspection_run

CHROMIUM = shutil.which('chromium') or shutil.which('chromium-browser')
BROWSER_S = 120     # a cold Chromium on a busy machine
NO_CHROMIUM = 'headless Chromium is not installed (Debian package chromium, scripts/debian-packages.txt)'
needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason=NO_CHROMIUM)
#: The findings' marker colour on the map (report.map_svg).
MARKER_RGB = (0xdd, 0x22, 0x22)


def _browser(*args):
    """Run headless Chromium with ``args``; its stdout."""
    command = [CHROMIUM, '--headless', '--no-sandbox', '--disable-gpu', '--hide-scrollbars'] + list(args)
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=BROWSER_S)
    assert done.returncode == 0, done.stderr.decode(errors='replace')[-2000:]
    return done.stdout.decode('utf-8', 'replace')


def _text(dom):
    """The visible text of a dumped DOM (tags and data URIs out)."""
    return re.sub(r'\s+', ' ', re.sub(r'<[^>]+>', ' ', dom))


@pytest.fixture(scope='module')
def written(tmp_path_factory):
    folder = str(tmp_path_factory.mktemp('inspection') / 'run')
    inspection_run.record(folder)
    assert report.main([folder]) == 0
    return folder, os.path.join(folder, 'report.html')


@needs_chromium
def test_the_report_in_a_browser_shows_every_finding_and_the_dig_list_in_order(written):
    _, page = written
    dom = _browser('--dump-dom', 'file://' + page)
    text = _text(dom)
    for number, (kind, note, _, _, _, _, _) in enumerate(inspection_run.MARKED, 1):
        assert 'Finding %d: %s' % (number, kind) in text and note in text
    digs = re.findall(r'dig at ([0-9.]+) m \(\+/- 0.16 m\) from the launch pit along the route', text)
    assert digs == ['0.60', '1.70', '2.70']          # leak, deposit, corrosion: 1.0, 2.1, 3.1 m on the map
    assert len(re.findall(r'<img [^>]*src="data:image/png;base64,', dom)) == 2 * len(inspection_run.MARKED)
    assert 'No mission in this run' in text


@needs_chromium
def test_the_report_in_a_browser_draws_the_map_with_the_findings(written, tmp_path):
    _, page = written
    shot = str(tmp_path / 'report.png')
    _browser('--screenshot=%s' % shot, '--window-size=1000,1400', 'file://' + page)
    image = Image.open(shot).convert('RGB')
    red = sum(1 for pixel in image.getdata() if pixel == MARKER_RGB)
    assert red > 3 * 50, 'the findings\' markers are not drawn (%d marker pixels)' % red


def test_the_report_is_self_contained(written):
    _, page = written
    with open(page) as stream:
        text = stream.read()
    assert not re.search(r'(src|href)="(?!data:)', text) and '<link' not in text


def test_the_report_merges_the_recorders_timeline_the_mission_log_and_the_findings(tmp_path):
    folder = str(tmp_path / 'run')
    inspection_run.record(folder)
    store.RunStore(folder).log_event({'stamp_s': 7.0, 'text': 'step 2/9: DRIVE, running', 'along_mm': 500.0})
    with open(os.path.join(folder, 'mission.jsonl'), 'w') as stream:
        stream.write('{"stamp_s": 5.0, "text": "step 1/9: CLAMP_STRAIGHT", "along_mm": 400}\n'
                     '{"stamp_s": 25.0, "text": "mission succeeded"}\nnot json\n')
    page, warnings = report.build(folder)
    order = [page.index(s) for s in ('step 1/9', 'step 2/9', 'finding 1 marked', 'finding 2 marked',
                                     'mission succeeded')]
    assert order == sorted(order) and any('line 3: skipped' in w for w in warnings)


def test_a_missing_run_is_a_clear_error(tmp_path, capsys):
    assert report.main([str(tmp_path / 'nowhere')]) == 1
    assert 'no such run folder' in capsys.readouterr().err


def test_an_empty_run_is_a_clear_error(tmp_path, capsys):
    assert report.main([str(tmp_path)]) == 1
    assert 'nothing was marked' in capsys.readouterr().err
    open(str(tmp_path / store.FINDINGS_FILE), 'w').close()
    assert report.main([str(tmp_path)]) == 1
    assert 'has no finding' in capsys.readouterr().err


def test_a_corrupt_run_is_a_clear_error_and_a_cut_short_line_only_a_warning(tmp_path, capsys):
    folder = str(tmp_path / 'run')
    inspection_run.record(folder)
    with open(os.path.join(folder, store.FINDINGS_FILE), 'a') as stream:
        stream.write('{"number": 4, "ki')
    assert report.main([folder]) == 0
    assert 'cut short' in capsys.readouterr().err
    with open(os.path.join(folder, store.FINDINGS_FILE), 'a') as stream:
        stream.write('\n{"number": 5}\n{"number": 6}\n')
    assert report.main([folder]) == 1
    assert 'corrupt' in capsys.readouterr().err


def test_a_run_whose_map_cannot_be_read_is_a_clear_error(tmp_path, capsys):
    folder = str(tmp_path / 'run')
    inspection_run.record(folder)
    assert report.main([folder, '--map', 'no_such_world']) == 1
    assert 'map of the run' in capsys.readouterr().err


def test_a_missing_frame_is_shown_as_missing(tmp_path):
    folder = str(tmp_path / 'run')
    inspection_run.record(folder)
    os.remove(os.path.join(folder, 'finding_002_rear.png'))
    page, warnings = report.build(folder)
    assert 'frame finding_002_rear.png missing' in page and any('finding_002_rear.png' in w for w in warnings)


def test_a_run_that_names_no_map_is_reported_without_one_and_says_so(tmp_path):
    folder = str(tmp_path / 'run')
    inspection_run.record(folder)
    store.write_about(folder, {'run': 'no map'})
    page, warnings = report.build(folder)
    assert '<svg' not in page and any('names no map' in w for w in warnings)
    assert page.count('class="finding"') == len(inspection_run.MARKED)
