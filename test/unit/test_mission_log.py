"""The mission executive's log on disk (pirate.supervisory.mission_log):
written as it goes, so an executive that dies mid-mission loses nothing,
and a restarted one says how the last mission ended."""
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

from pirate.supervisory import mission_log

from test_executive import FakeRobot, WAIT_S, mission

HERE = os.path.dirname(os.path.abspath(__file__))


def test_a_finished_mission_is_read_back_as_it_ended(tmpdir):
    path = str(tmpdir.join('mission_log.jsonl'))
    log = mission_log.MissionLog(path)
    outcome = mission(FakeRobot(0.3), journal=log.write, name='test: pit -> target').run()
    log.close()
    ending = mission_log.last_ending(mission_log.read(path))
    assert (ending.mission, ending.status, ending.message) == ('test: pit -> target', 'succeeded', outcome.message)
    said = [r['text'] for r in mission_log.read(path) if r['event'] == 'say']
    assert said == outcome.log


def test_the_log_of_a_mission_still_running_is_on_disk_step_by_step(tmpdir):
    """The mission's log survived only in rosout: it was kept in memory
    until the mission's result, which an executive killed mid-mission never sent."""
    path = str(tmpdir.join('mission_log.jsonl'))
    robot = FakeRobot(0.3, hold_step='DRIVE')
    run = mission(robot, journal=mission_log.MissionLog(path).write)
    thread = threading.Thread(target=run.run, daemon=True)
    thread.start()
    assert robot.entered.wait(WAIT_S)                       # the Drive, step 2, runs now
    ending = mission_log.last_ending(mission_log.read(path))  # what a restarted executive reads
    assert ending.status == 'interrupted' and ending.step == 2 and 'step 2 of 5' in ending.message
    assert 'DRIVE' in ending.message
    run.cancel()
    thread.join(WAIT_S)
    assert mission_log.last_ending(mission_log.read(path)).status == 'cancelled'


def test_an_executive_killed_mid_mission_leaves_its_whole_log(tmpdir):
    """SIGKILL: no handler runs, nothing buffered in the process survives."""
    path = str(tmpdir.join('mission_log.jsonl'))
    script = textwrap.dedent('''
        import sys, threading
        sys.path.insert(0, %r)
        from pirate.supervisory import mission_log
        from test_executive import FakeRobot, mission
        robot = FakeRobot(0.3, hold_step='DRIVE')
        mission(robot, journal=mission_log.MissionLog(%r).write).run()
        ''' % (HERE, path))
    executive = subprocess.Popen([sys.executable, '-c', script])
    try:
        deadline = time.monotonic() + 30.0
        while time.monotonic() < deadline and not _says(path, 'step 2/5: DRIVE'):
            time.sleep(0.05)                               # polling the file, not a synchronisation
        assert _says(path, 'step 2/5: DRIVE')
    finally:
        executive.send_signal(signal.SIGKILL)
        executive.wait(10.0)
    ending = mission_log.last_ending(mission_log.read(path))
    assert ending.status == 'interrupted' and ending.step == 2, ending


def test_a_line_cut_short_by_a_death_mid_write_is_left_out(tmpdir):
    path = str(tmpdir.join('mission_log.jsonl'))
    log = mission_log.MissionLog(path, clock=lambda: 5.0)
    log.write({'event': 'start', 'mission': 'm', 'steps': 3})
    log.write({'event': 'say', 'step': 1, 'text': 'step 1/3: CLAMP_STRAIGHT'})
    log.close()
    with open(path, 'a') as cut:
        cut.write('{"event": "say", "step": 2, "te')
    ending = mission_log.last_ending(mission_log.read(path))
    assert ending == mission_log.Ending('m', 'interrupted', 'the executive stopped during step 1 of 3; the last it '
                                        'said: step 1/3: CLAMP_STRAIGHT', 1, 3)
    assert mission_log.describe(None) == 'no mission in the log'


def _says(path, text):
    return any(text in r.get('text', '') for r in mission_log.read(path))
