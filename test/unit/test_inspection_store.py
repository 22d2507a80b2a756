"""Findings survive the recorder's death: written as they happen, read back
by a new recorder; a line cut short is skipped, corruption is named."""
import json
import os

import pytest

from pirate.inspection import store

import inspection_run


def test_findings_survive_a_restart_of_the_recorder(tmp_path):
    folder = str(tmp_path / 'run')
    inspection_run.record(folder)           # the recorder that wrote them is gone with this call
    again = store.RunStore(folder)
    assert [f['kind'] for f in again.findings] == ['corrosion', 'leak', 'deposit']
    assert again.warnings == [] and again.next_number() == 4
    for finding in again.findings:
        for name in finding['frames'].values():
            assert os.path.getsize(os.path.join(folder, name)) > 0


def test_a_restarted_recorder_goes_on_numbering_and_keeps_run_json(tmp_path):
    folder = str(tmp_path / 'run')
    inspection_run.record(folder)
    again = store.RunStore(folder, {'run': 'another', 'map': 'straight_90'})
    again.append({'number': again.next_number(), 'kind': 'water', 'position': {'along_mm': 500.0}})
    findings, _ = store.read_findings(folder)
    assert [f['number'] for f in findings] == [1, 2, 3, 4]
    assert store.read_about(folder)['map'] == inspection_run.MAP


def test_a_last_line_cut_short_is_skipped_with_a_warning_and_the_next_finding_is_kept(tmp_path):
    folder = str(tmp_path / 'run')
    inspection_run.record(folder)
    with open(os.path.join(folder, store.FINDINGS_FILE), 'a') as stream:
        stream.write('{"number": 4, "kind": "le')            # the node died here
    again = store.RunStore(folder)
    assert len(again.findings) == 3
    assert len(again.warnings) == 1 and 'line 4: skipped, cut short' in again.warnings[0]
    again.append({'number': 4, 'kind': 'leak', 'position': {'along_mm': 900.0}})
    findings, warnings = store.read_findings(folder)
    assert [f['number'] for f in findings] == [1, 2, 3, 4] and len(warnings) == 1


def test_a_corrupt_line_before_the_end_is_an_error_naming_it(tmp_path):
    folder = str(tmp_path / 'run')
    inspection_run.record(folder)
    path = os.path.join(folder, store.FINDINGS_FILE)
    with open(path) as stream:
        lines = stream.read().splitlines()
    lines[1] = json.dumps({'no': 'finding'})
    with open(path, 'w') as stream:
        stream.write('\n'.join(lines) + '\n')
    with pytest.raises(store.RunError, match='line 2: corrupt'):
        store.read_findings(folder)


def test_a_missing_folder_or_findings_file_is_a_clear_error(tmp_path):
    with pytest.raises(store.RunError, match='no such run folder'):
        store.read_findings(str(tmp_path / 'nowhere'))
    with pytest.raises(store.RunError, match='nothing was marked'):
        store.read_findings(str(tmp_path))


def test_a_restarted_recorder_goes_on_with_the_current_run_unless_told_to_start_anew(tmp_path):
    root = str(tmp_path)
    first = store.current_run(root)
    assert store.current_run(root) == first
    import datetime
    later = store.current_run(root, new=True, now=datetime.datetime(2030, 1, 2, 3, 4, 5))
    assert later == 'run-20300102-030405' and store.current_run(root) == later
    again = store.current_run(root, new=True, now=datetime.datetime(2030, 1, 2, 3, 4, 5))
    assert again == 'run-20300102-030405-2'
