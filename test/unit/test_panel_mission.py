"""The panel's mission controls (bad input: a panel that
disconnects mid-mission): the map's mission buttons, their LEDs, Stop,
the panel's presence, and the Mapper driving a real mission executive.

No ROS: the Mapper with real Setpoint/Control/Limit objects (test_mapper's
rig), the executive with test_executive's scripted robot. Threads meet on
conditions, never on sleeps."""
import queue
import threading

import pytest
import yaml

from pirate.panel import config as panel_config
from pirate.panel import mission_buttons
from pirate.panel.mapper import Mapper
from pirate.panel.presence import PanelPresence
from pirate.robot import safety, tables
from pirate.supervisory import executive as ex

from test_executive import WAIT_S, FakeRobot, Waiter, mission
from test_mapper import CONFIG, PRESS, RELEASE, Rig

PLAY, STOP, REWIND = 41, 42, 43
M2_CONFIRM, M3_PAUSE, M4_RESUME, M5_FULL, M6_CONFIRM, M7_MANUAL = 49, 50, 51, 52, 53, 54
TRACK_NEXT, MARKER_NEXT, MARKER_BACK, CYCLE, TRACK_BACK, R1 = 59, 62, 61, 46, 58, 64


class Commands(object):
    """The mission client contract: ``command(text)``; answers come later."""

    def __init__(self):
        self.sent = []

    def command(self, text):
        self.sent.append(text)


def rig_with(client):
    rig = Rig()
    rig.mapper = Mapper(panel_config.load(CONFIG), rig.setpoint, rig.control, rig.limit, rig.pab,
                        rig.leds.__setitem__, rig.logs.append, rig.clock, mission=client)
    return rig


def pab_mode(rig):
    rig.press(REWIND)
    rig.press(PLAY)


def feedback(pab='DRIVE', option='', distance_mm=250.0, level=ex.CONFIRM, waiting_for=''):
    return ex.Progress(2, 5, pab, option, distance_mm, 0.5, 60.0, level, 'waiting' if waiting_for else 'running',
                       waiting_for)


WAITING = '%s of step 2 (DRIVE)' % ex.WAIT_CONFIRM


# --- the map ---------------------------------------------------------------

def test_the_m_row_is_the_mission_in_pab_mode_and_keeps_its_manual_job():
    cfg = panel_config.load(CONFIG)
    assert {ch: b.command for ch, b in cfg.mission_buttons.items()} == {
        M2_CONFIRM: 'confirm', M3_PAUSE: 'pause', M4_RESUME: 'resume', M5_FULL: 'level full',
        M6_CONFIRM: 'level confirm', M7_MANUAL: 'level manual'}
    for channel in cfg.mission_buttons:
        assert cfg.channels[channel].action == 'single_stop' and cfg.channels[channel].modes == ('manual',)


@pytest.mark.parametrize('button, reason', [
    ({'channel': 50, 'control': 'M 3', 'command': 'jump'}, 'unknown command'),
    ({'channel': 59, 'control': 'track >', 'command': 'pause'}, 'already acts in PAB mode'),
    ({'channel': 47, 'control': 'nothing', 'command': 'pause'}, 'not on the panel map'),
    ({'channel': 50, 'command': 'pause', 'led': 1}, 'nothing else')])
def test_a_bad_mission_button_is_refused_when_the_map_is_loaded(button, reason):
    with open(CONFIG) as stream:
        params = yaml.safe_load(stream)
    params['mission_buttons'] = [button]
    with pytest.raises(panel_config.ConfigError, match=reason):
        panel_config.from_params(params)


def test_m_buttons_send_mission_commands_in_pab_mode_and_stop_joints_in_manual():
    client = Commands()
    rig = rig_with(client)
    rig.play()
    rig.press(M3_PAUSE)                  # manual: immediate stop of Bend III, as before
    assert client.sent == []
    assert rig.control.get(tables.element('bend_iii').index) == safety.COMMAND_CODES['single_stop']
    rig.press(STOP)
    assert client.sent == ['cancel']     # Stop: a mission on its way to the executive is cancelled too
    del client.sent[:]
    pab_mode(rig)
    for channel in (M2_CONFIRM, M3_PAUSE, M4_RESUME, M6_CONFIRM):
        rig.mapper.handle(channel, PRESS)
        rig.mapper.handle(channel, PRESS)    # the panel repeats: one command per press
        rig.mapper.handle(channel, RELEASE)
    assert client.sent == ['confirm', 'pause', 'resume', 'level confirm']


# --- LEDs --------------------------------------------------------------------

def _led_history(rig, ticks, channel):
    seen = []
    for _ in range(ticks):
        rig.mapper.tick()
        seen.append(rig.leds.get(channel))
    return seen


def test_a_step_waiting_for_confirmation_blinks_confirm_and_its_pab_button():
    rig = rig_with(Commands())
    pab_mode(rig)
    rig.mapper.mission_progress(feedback(waiting_for=WAITING))
    for channel in (M2_CONFIRM, MARKER_NEXT):             # DRIVE forwards is marker >
        seen = _led_history(rig, 12, channel)
        assert True in seen and False in seen, (channel, seen)
    assert set(_led_history(rig, 12, MARKER_BACK)) == {False}   # the other direction does not blink
    assert rig.leds[M6_CONFIRM] and not rig.leds[M5_FULL] and not rig.leds[M7_MANUAL]
    rig.mapper.mission_progress(feedback())                 # confirmed: running
    assert set(_led_history(rig, 6, M2_CONFIRM)) == {False}


def test_pause_lit_while_paused_and_dark_in_manual_mode():
    rig = rig_with(Commands())
    pab_mode(rig)
    rig.mapper.mission_progress(feedback(waiting_for='%s (paused)' % ex.WAIT_RESUME))
    rig.mapper.tick()
    assert rig.leds[M3_PAUSE]
    rig.mapper.mission_ended('cancelled', 'by the operator')
    rig.mapper.tick()
    assert not rig.leds[M3_PAUSE]


def test_a_level_the_executive_accepted_lights_its_button():
    rig = rig_with(Commands())
    pab_mode(rig)
    rig.mapper.mission_reply('level manual', True, 'autonomy level manual for the next mission')
    rig.mapper.tick()
    assert rig.leds[M7_MANUAL] and not rig.leds[M5_FULL]
    rig.mapper.mission_reply('level full', False, 'no mission executive answers')
    rig.mapper.tick()
    assert rig.leds[M7_MANUAL] and any('refused' in line for line in rig.logs)


# --- PAB buttons and Stop during a mission ----------------------------------------

def test_the_waiting_pabs_button_confirms_and_other_pab_buttons_are_refused():
    client = Commands()
    rig = rig_with(client)
    pab_mode(rig)
    rig.mapper.mission_progress(feedback(waiting_for=WAITING))
    rig.press(TRACK_NEXT)
    assert rig.pab.goals == [] and client.sent == []
    assert any('a mission is running' in line for line in rig.logs)
    rig.press(MARKER_NEXT)
    assert rig.pab.goals == [] and client.sent == ['confirm']


def test_stop_cancels_the_mission_and_its_running_pab():
    client = Commands()
    rig = rig_with(client)
    pab_mode(rig)
    rig.mapper.mission_progress(feedback(level=ex.FULL))
    rig.pab.active = True
    rig.press(STOP)
    assert client.sent == ['cancel'] and rig.pab.cancels == 1 and not rig.mapper.playing


def test_stop_before_the_mission_was_taken_in_cancels_it_and_an_idle_stop_tells_nothing():
    """Stop while a mission was on its way (no feedback yet) stopped the panel
    but not the mission: its first PAB was refused, "the operator panel is
    stopped", and it ended aborted rather than cancelled."""
    client = Commands()
    rig = rig_with(client)
    pab_mode(rig)
    rig.press(STOP)
    assert client.sent == ['cancel']
    told = list(rig.logs)
    rig.mapper.mission_reply('cancel', True, 'no mission is running; one sent before now is cancelled when it comes')
    rig.mapper.mission_reply('cancel', False, 'no mission executive answers')
    assert rig.logs == told


# --- a panel that disconnects ------------------------------------------------------

def test_a_disconnect_pauses_a_running_mission_once_with_the_reason():
    client = Commands()
    rig = rig_with(client)
    rig.mapper.panel_connected(False, 'no node publishes panel events any more')
    assert client.sent == []                              # no mission: nothing to pause
    rig.mapper.mission_progress(feedback(level=ex.FULL))
    rig.mapper.panel_connected(False, 'the MIDI driver lost the panel device')
    assert client.sent == ['pause the operator panel disconnected (the MIDI driver lost the panel device)']
    rig.mapper.mission_progress(feedback(level=ex.FULL, waiting_for='%s (paused)' % ex.WAIT_RESUME))
    rig.mapper.panel_connected(False, 'again')
    rig.mapper.panel_connected(True, 'a node publishes panel events')
    assert len(client.sent) == 1                          # already paused; a reconnect resumes nothing
    assert any('stays paused' in line for line in rig.logs)


@pytest.mark.parametrize('events, changes', [
    ([('pub', 0), ('pub', 0)], []),                                   # never a panel: nothing to lose
    ([('pub', 1), ('pub', 1), ('pub', 0)], [True, False]),           # virtual panel closed
    ([('pub', 1), ('dev', False), ('pub', 1), ('dev', True), ('pub', 1)], [True, False, True]),  # unplugged
    ([('dev', False), ('pub', 1), ('dev', True), ('pub', 1)], [True])])   # driver up before its device
def test_presence_reports_a_panel_lost_only_after_it_was_seen(events, changes):
    presence, seen = PanelPresence(), []
    for kind, value in events:
        if kind == 'dev':
            presence.device(value)
        else:
            change = presence.update(value)
            if change is not None:
                seen.append(change[0])
                assert change[1]
    assert seen == changes


# --- the panel driving the executive -----------------------------------------------

class ExecutiveClient(object):
    """The ROS edge's contract in process: commands run on a worker thread
    (as MissionCommandClient's service calls do); answers go back to the Mapper."""

    def __init__(self):
        self.run, self.reply, self._todo = None, None, queue.Queue()
        threading.Thread(target=self._work, daemon=True).start()

    def command(self, text):
        self._todo.put(text)

    def _work(self):
        while True:
            text = self._todo.get()
            self.reply(text, *self.run.command(text))


def _panel_and_mission(robot, level):
    client, waiter = ExecutiveClient(), Waiter()
    rig = rig_with(client)
    client.reply = rig.mapper.mission_reply

    def progress(p):
        rig.mapper.mission_progress(p)
        waiter(p)
    client.run = mission(robot, progress=progress, level=level)
    result = {}
    thread = threading.Thread(target=lambda: result.update(outcome=client.run.run()), daemon=True)
    return rig, waiter, thread, result


def test_confirm_level_from_the_panel_each_pab_confirmed_by_its_blinking_button_or_m2():
    robot = FakeRobot(0.3)
    rig, waiter, thread, result = _panel_and_mission(robot, ex.CONFIRM)
    pab_mode(rig)
    thread.start()
    # The plan: CLAMP_SIDEWAYS LEFT (R 1), DRIVE + (marker >), MITRE_BEND LEFT (cycle), DRIVE +, HOME (track <).
    for number, button in enumerate((R1, MARKER_NEXT, CYCLE, M2_CONFIRM, TRACK_BACK), 1):
        waiter.wait_for(lambda p, n=number: p.waiting_for.startswith('%s of step %d' % (ex.WAIT_CONFIRM, n)))
        assert len(robot.goals) == number - 1
        rig.press(button)
    thread.join(WAIT_S)
    assert result['outcome'].status == 'succeeded' and rig.pab.goals == []
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND', 'DRIVE', 'HOME']


def _in_its_first_drive(robot):
    """A level-full mission started from the panel in PAB mode, its first drive running."""
    rig, waiter, thread, result = _panel_and_mission(robot, ex.FULL)
    pab_mode(rig)
    thread.start()
    assert robot.entered.wait(WAIT_S)
    return rig, waiter, thread, result


def test_pause_and_resume_from_the_panel_and_stop_ends_the_mission():
    robot = FakeRobot(0.3, hold_step='DRIVE')
    rig, waiter, thread, result = _in_its_first_drive(robot)
    rig.press(M3_PAUSE)
    waiter.wait_for(lambda p: p.waiting_for.startswith(ex.WAIT_RESUME))
    rig.press(M6_CONFIRM)                 # level confirm: the resumed step waits for it too
    rig.press(M4_RESUME)
    waiter.wait_for(lambda p: p.waiting_for.startswith('%s of step 2' % ex.WAIT_CONFIRM))
    rig.press(STOP)                       # no PAB runs: Stop still ends the mission
    thread.join(WAIT_S)
    outcome = result['outcome']
    assert outcome.status == 'cancelled'
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE']
    assert any(line.startswith('pause asked') for line in outcome.log)


class CountingRobot(FakeRobot):
    cancels = 0

    def cancel(self):
        self.cancels += 1
        FakeRobot.cancel(self)


def test_a_panel_lost_mid_mission_pauses_it_safe_and_the_log_keeps_why():
    robot = CountingRobot(0.3, hold_step='DRIVE')
    rig, waiter, thread, result = _in_its_first_drive(robot)
    rig.mapper.panel_connected(False, 'the MIDI driver lost the panel device')
    waiter.wait_for(lambda p: p.waiting_for.startswith(ex.WAIT_RESUME))
    # The running drive was cancelled (the server's safe hold) and nothing else ran.
    assert robot.cancels == 1 and [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE']
    rig.mapper.panel_connected(True, 'a node publishes panel events')
    rig.press(M4_RESUME)
    thread.join(WAIT_S)
    outcome = result['outcome']
    assert outcome.status == 'succeeded', outcome.message
    assert any('operator panel disconnected' in line and 'MIDI driver' in line for line in outcome.log)


def test_a_mission_whose_executive_falls_silent_is_dropped_and_pab_buttons_work_again():
    watch = mission_buttons.ExecutiveWatch(3.0)
    assert not watch.lost(10.0, active=False)
    watch.heard(10.0)
    assert not watch.lost(12.0, active=True)
    watch.heard(12.5)
    assert not watch.lost(15.0, active=True) and watch.lost(15.6, active=True)
    assert not watch.lost(16.0, active=False)
    assert not watch.lost(30.0, active=True) and watch.lost(33.1, active=True)   # active, never heard since
    rig = rig_with(Commands())
    pab_mode(rig)
    rig.mapper.mission_progress(feedback(level=ex.FULL))
    rig.press(TRACK_NEXT)
    assert rig.pab.goals == []
    rig.mapper.mission_ended('lost', 'no word from the mission executive for 3 s')
    rig.press(TRACK_NEXT)
    assert len(rig.pab.goals) == 1
