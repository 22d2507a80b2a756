"""Virtual panel without ROS: synthesised pygame events -> (channel, value);
LED state -> pixels; a screenshot under Xvfb shows the panel."""
import os
import shutil
import subprocess
import sys

os.environ.setdefault('SDL_VIDEODRIVER', 'dummy')
os.environ.setdefault('PYGAME_HIDE_SUPPORT_PROMPT', '1')

import numpy  # noqa: E402
import pygame  # noqa: E402
import pytest  # noqa: E402

from pirate.panel import virtual  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))


@pytest.fixture
def panel():
    pygame.display.init()
    pygame.font.init()
    yield virtual.VirtualPanel()
    pygame.display.quit()


def click(panel, channel):
    pos = panel.control(channel).rect.center
    down = panel.handle_event(pygame.event.Event(pygame.MOUSEBUTTONDOWN, button=1, pos=pos))
    up = panel.handle_event(pygame.event.Event(pygame.MOUSEBUTTONUP, button=1, pos=pos))
    return down + up


@pytest.mark.parametrize('channel', [41, 42, 43, 59, 60, 32, 39, 48, 55, 64, 71, 46, 61, 62, 44, 45, 58])
def test_click_on_a_button_presses_and_releases_it(panel, channel):
    assert click(panel, channel) == [(channel, 127), (channel, 0)]


def test_every_nanokontrol2_control_is_there(panel):
    channels = {c.channel for c in panel.controls}
    expected = set(range(0, 8)) | set(range(16, 24)) | set(range(32, 40)) | set(range(48, 56)) \
        | set(range(64, 72)) | {41, 42, 43, 44, 45, 46, 58, 59, 60, 61, 62}
    assert channels == expected


def test_dragging_a_slider_sends_its_values(panel):
    rect = panel.control(4).rect
    events = panel.handle_event(pygame.event.Event(pygame.MOUSEBUTTONDOWN, button=1, pos=(rect.centerx, rect.top)))
    assert events == [(4, 127)]
    events = panel.handle_event(pygame.event.Event(pygame.MOUSEMOTION, pos=(rect.centerx, rect.bottom), rel=(0, 1), buttons=(1, 0, 0)))
    assert events == [(4, 0)]
    panel.handle_event(pygame.event.Event(pygame.MOUSEBUTTONUP, button=1, pos=(rect.centerx, rect.bottom)))
    assert panel.handle_event(pygame.event.Event(pygame.MOUSEMOTION, pos=rect.center, rel=(0, 1), buttons=(0, 0, 0))) == []


def test_the_wheel_over_a_slider_or_knob_nudges_it_and_not_a_button(panel):
    """The wheel arrives as mouse buttons 4 (up) and 5 (down): so on
    pygame 1.9.6, and pygame 2 sends them beside its MOUSEWHEEL."""
    wheel = lambda button, pos: panel.handle_event(pygame.event.Event(pygame.MOUSEBUTTONDOWN, button=button, pos=pos))
    slider, knob = panel.control(4).rect.center, panel.control(20).rect.center
    start = panel.values[4]
    assert wheel(4, slider) == [(4, start + 2)]
    assert wheel(5, slider) == [(4, start)]
    assert wheel(4, knob) == [(20, 2)]
    assert wheel(5, knob) == [(20, 0)]
    assert wheel(4, panel.control(41).rect.center) == []
    assert panel.handle_event(pygame.event.Event(pygame.MOUSEBUTTONUP, button=4, pos=slider)) == []


def test_keyboard_selects_a_strip_and_moves_its_controls(panel):
    key = lambda k, t=pygame.KEYDOWN: panel.handle_event(pygame.event.Event(t, key=k, mod=0, unicode=''))
    key(pygame.K_5)
    assert key(pygame.K_UP) == [(4, 67)]
    assert key(pygame.K_RIGHT) == [(20, 4)]
    assert key(pygame.K_s) == [(36, 127)] and key(pygame.K_s, pygame.KEYUP) == [(36, 0)]
    assert key(pygame.K_SPACE) == [(42, 127)]
    for _ in range(40):
        key(pygame.K_PAGEUP)
    assert panel.values[4] == 127   # held within 0-127


def test_led_message_changes_what_is_drawn(panel):
    surface = pygame.Surface((virtual.WIDTH, virtual.HEIGHT), 0, virtual.DEPTH_BITS)
    point = panel.control(43).rect.move(3, 3).topleft
    panel.draw(surface)
    assert tuple(surface.get_at(point))[:3] == virtual.BUTTON_OFF
    panel.set_led(43, True)
    panel.draw(surface)
    assert tuple(surface.get_at(point))[:3] == virtual.BUTTON_LIT
    assert panel.operation_mode == 'PAB'


SHOT = r'''
import os, sys
import pygame
from pirate.panel import virtual
pygame.display.init()
screen = pygame.display.set_mode((virtual.WIDTH, virtual.HEIGHT), 0, virtual.DEPTH_BITS)
print(pygame.display.get_driver())
panel = virtual.VirtualPanel()
for button in (41, 43, 36, 59):
    panel.set_led(button, True)
panel.pab_text = 'PAB running: Clamp Straight / moving front / move front front_tilt 0.21/0.40 (2.1 of 15 s)'
panel.operator_text = 'PAB Clamp Straight: sent'
panel.draw(screen)
pygame.display.flip()
pygame.image.save(screen, sys.argv[1])
'''


def _free_display():
    """A display number no X server holds: neither its socket nor its lock
    file is there (Xvfb's own choice, -displayfd alone, took one whose
    socket another Xvfb held without a lock file, and no client could
    connect to it)."""
    return next(n for n in range(100, 1000)
                if not os.path.exists('/tmp/.X11-unix/X%d' % n) and not os.path.exists('/tmp/.X%d-lock' % n))


def _shoot_under_xvfb(path):
    """Run SHOT on a fresh Xvfb; the finished process (None: no X server to open)."""
    # Xvfb writes the display's number to the pipe once it accepts clients
    # (its socket file appears earlier: SDL 1.2 came too soon).
    ready, write_end = os.pipe()
    xvfb = subprocess.Popen(['Xvfb', ':%d' % _free_display(), '-displayfd', str(write_end), '-screen', '0',
                             '1280x768x24', '-nolisten', 'tcp'],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, pass_fds=(write_end,))
    os.close(write_end)
    try:
        with os.fdopen(ready) as numbers:
            display = numbers.readline().strip()
        assert display, 'Xvfb did not start'
        env = dict(os.environ, DISPLAY=':%s' % display, SDL_VIDEODRIVER='x11')
        run = subprocess.run([sys.executable, '-c', SHOT, path], env=env, timeout=30,
                             capture_output=True, text=True)
    finally:
        xvfb.terminate()
        xvfb.wait(timeout=10)
    return None if "Couldn't open X11 display" in run.stderr else run


@pytest.mark.skipif(shutil.which('Xvfb') is None, reason='Xvfb is not installed')
@pytest.mark.skipif(pygame.version.vernum[0] < 2, reason="pygame 1.9.6 (SDL 1.2) could not open an Xvfb display beside "
                    "8 busy processes (3 of 3: Couldn't open X11 display); pygame 2's tier checks the X11 path")
def test_screenshot_under_xvfb_shows_the_panel():
    """Beside another test tier's Xvfb (make test runs two at once): a
    fresh Xvfb on a free display, up to three, if the client cannot open one."""
    out_dir = os.path.join(ROOT, 'test-results')
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, 'virtual_panel.png')
    if os.path.exists(path):
        os.remove(path)
    run = None
    for _ in range(3):
        run = _shoot_under_xvfb(path)
        if run is not None:
            break
    assert run is not None, 'no Xvfb display could be opened, three tries'
    assert run.returncode == 0, run.stderr
    assert 'x11' in run.stdout
    image = pygame.image.load(path)
    assert image.get_size() == (virtual.WIDTH, virtual.HEIGHT)
    panel = virtual.VirtualPanel()
    lit = panel.control(43).rect.move(3, 3).topleft
    dark = panel.control(42).rect.move(3, 3).topleft
    assert tuple(image.get_at(lit))[:3] == virtual.BUTTON_LIT
    assert tuple(image.get_at(dark))[:3] == virtual.BUTTON_OFF
    assert tuple(image.get_at((virtual.WIDTH // 2, virtual.HEIGHT - 8)))[:3] == virtual.BODY


def test_feedback_line_shows_the_numbers_and_idle_state():
    virtual_node = pytest.importorskip('pirate.panel.virtual_node')
    msg = pytest.importorskip('pirate.msg')
    fb = msg.PirateFeedback(server_state='Clamp Straight', pab_state='clamping rear', primitive='clamp rear',
                            guard='bend_iv <= -0.77 and bend_iii >= 0.35', elapsed=2.5, timeout=15.0,
                            guard_joints=['bend_iv', 'bend_iii'], guard_values=[-0.5, 0.2],
                            guard_thresholds=[-0.77, 0.35])
    line = virtual_node.feedback_text(fb)
    assert 'clamp rear bend_iv -0.50/-0.77 bend_iii 0.20/0.35 (2.5 of 15 s)' in line
    idle = virtual_node.feedback_text(msg.PirateFeedback(server_state='Idle Partly Clamped (front full, '
                                                                      'rear free)'))
    assert idle.startswith('Server: Idle Partly Clamped') and 'running' not in idle


def test_mission_line_shows_the_step_the_level_and_what_it_waits_for(panel):
    virtual_node = pytest.importorskip('pirate.panel.virtual_node')
    msg = pytest.importorskip('pirate.msg')
    fb = msg.MissionFeedback(step=3, steps=9, pab='MITRE_BEND', along_mm=1885.4, time_left_s=212.0,
                             level='confirm', state='waiting', waiting_for='confirmation of step 3 (MITRE_BEND)')
    line = virtual_node.mission_text(fb)
    assert line == ('step 3/9 MITRE_BEND at 1885 mm, level confirm, about 212 s left, '
                    'WAITING for confirmation of step 3 (MITRE_BEND)')
    assert 'WAITING' not in virtual_node.mission_text(msg.MissionFeedback(step=1, steps=2, pab='DRIVE'))
    panel.mission_text = line
    assert panel.status_lines()[3] == 'Mission: ' + line
    panel.mission_text = ''
    assert panel.status_lines()[3] == ''


def test_mission_line_names_the_mission_and_the_steps_option(panel):
    virtual_node = pytest.importorskip('pirate.panel.virtual_node')
    msg = pytest.importorskip('pirate.msg')
    name = virtual_node.mission_name(msg.MissionGoal(map='inspection_tee_90', points=['launch_pit', 'target']))
    fb = msg.MissionFeedback(step=3, steps=5, pab='T_JOINT', option='STRAIGHT', along_mm=785.0, time_left_s=99.0,
                             level='full', state='waiting', waiting_for='resume (paused)')
    assert virtual_node.mission_text(fb, name) == (
        'inspection_tee_90 launch_pit -> target: step 3/5 T_JOINT STRAIGHT at 785 mm, level full, '
        'about 99 s left, WAITING for resume (paused)')


def _label_pixels(panel, channel):
    """The pixels of the label drawn under a small button."""
    surface = pygame.Surface((virtual.WIDTH, virtual.HEIGHT), 0, virtual.DEPTH_BITS)
    panel.draw(surface)
    rect = panel.control(channel).rect
    area = pygame.Rect(rect.centerx - 30, rect.bottom + 2, 60, 14)
    return [tuple(surface.get_at((x, y))) for x in range(area.left, area.right) for y in range(area.top, area.bottom)]


def test_in_pab_mode_the_m_row_reads_its_mission_jobs(panel):
    """The M buttons stop joints in manual mode and control the
    mission in PAB mode (config/nanokontrol2.yaml mission_buttons); the
    virtual panel labels them for the mode in force."""
    from pirate import paths
    from pirate.panel import config, mission_buttons
    panel_map = config.load(os.path.join(paths.CONFIG_DIR, 'nanokontrol2.yaml'))
    panel.mission_labels = mission_buttons.labels(panel_map.mission_buttons)
    assert panel.mission_labels == {49: 'confirm', 50: 'pause', 51: 'resume', 52: 'full', 53: 'lvl conf',
                                    54: 'manual'}
    manual = _label_pixels(panel, 50)
    assert [panel.label(panel.control(c)) for c in (48, 49, 50)] == ['M', 'M', 'M']
    panel.set_led(virtual.OPERATION_MODE_BUTTON, True)          # PAB mode
    assert [panel.label(panel.control(c)) for c in range(48, 56)] == [
        'M', 'confirm', 'pause', 'resume', 'full', 'lvl conf', 'manual', 'M']
    assert _label_pixels(panel, 50) != manual                    # drawn, not only named
    assert [panel.label(panel.control(c)) for c in (32, 64)] == ['S', 'R']


def test_long_status_lines_are_wrapped_to_the_window_not_clipped(panel):
    panel.mission_text = ('inspection_network_90 launch_pit -> target: step 5/9 MITRE_BEND RIGHT at 1885 mm, level '
                          'confirm, about 212 s left, WAITING for confirmation of step 5 (MITRE_BEND RIGHT)')
    panel.draw(pygame.Surface((virtual.WIDTH, virtual.HEIGHT), 0, virtual.DEPTH_BITS))
    lines = panel.wrapped_status()
    assert all(panel._font.size(line)[0] <= virtual.PANEL_W - 28 for line in lines)   # pylint: disable=protected-access
    assert 'WAITING for confirmation of step 5 (MITRE_BEND RIGHT)' in ' '.join(lines)


def test_manual_mode_labels_what_each_slider_and_knob_moves(panel):
    panel.manual_labels = {7: 'wheels', 17: 'limit Bend IV'}
    surface = pygame.Surface((virtual.WIDTH, virtual.HEIGHT), 0, virtual.DEPTH_BITS)
    panel.draw(surface)
    rect = panel.control(7).rect
    under = pygame.Rect(rect.centerx - 25, rect.bottom + 18, 50, 12)
    labelled = {tuple(surface.get_at((x, y)))[:3] for x in range(under.left, under.right)
                for y in range(under.top, under.bottom)}
    assert labelled != {virtual.BODY}
    panel.set_led(virtual.OPERATION_MODE_BUTTON, True)          # PAB mode: no manual labels
    panel.draw(surface)
    plain = {tuple(surface.get_at((x, y)))[:3] for x in range(under.left, under.right)
             for y in range(under.top, under.bottom)}
    assert plain == {virtual.BODY}


def _camera_centre(panel, camera):
    """The colour drawn at the middle of ``camera``'s pane."""
    surface = pygame.Surface((virtual.WIDTH, virtual.HEIGHT), 0, virtual.DEPTH_BITS)
    panel.draw(surface)
    return tuple(surface.get_at(panel.camera_rect(virtual.CAMERAS.index(camera)).center))[:3]


@pytest.mark.parametrize('encoding, pixel, shown', [
    ('rgb8', (200, 30, 10), (200, 30, 10)),
    ('bgr8', (10, 30, 200), (200, 30, 10)),       # blue first on the wire: the same red
    ('mono8', (90,), (90, 90, 90)),
])
def test_a_camera_image_is_shown_right_of_the_panel_in_its_colours(panel, encoding, pixel, shown):
    width, height = 160, 120
    step = width * len(pixel) + 2                 # rows padded: the step is what counts
    row = bytes(pixel) * width + b'\0\0'
    before = _camera_centre(panel, 'front')
    panel.cameras['front'] = virtual.camera_surface(width, height, encoding, step, row * height)
    assert _camera_centre(panel, 'front') == shown != before
    assert _camera_centre(panel, 'rear') == before         # the other camera still has none


@pytest.mark.parametrize('width, height, encoding, step, size, said', [
    (160, 120, 'yuv422', 320, 320 * 120, 'a yuv422 image is not shown (rgb8, bgr8, mono8)'),
    (160, 120, '', 480, 480 * 120, 'a no-encoding image is not shown'),
    (160, 120, 'rgb8', 480, 480 * 119, 'needs 57600 bytes, not 57120'),
    (160, 120, 'rgb8', 100, 480 * 120, 'rows of 100 bytes'),
    (0, 120, 'rgb8', 480, 480 * 120, 'a 0 x 120 rgb8 image'),
])
def test_an_image_the_pane_cannot_show_says_why(panel, width, height, encoding, step, size, said):
    with pytest.raises(ValueError) as refused:
        virtual.camera_surface(width, height, encoding, step, bytes(size))
    assert said in str(refused.value)
    before = _camera_centre(panel, 'front')
    panel.cameras['front'] = str(refused.value)          # what the node shows instead
    assert _camera_centre(panel, 'front') == before      # the empty pane, with the reason in it


def test_a_large_image_is_sampled_down_to_no_less_than_the_pane():
    """A lab grabber's 1920 x 1080 frame: every 7th pixel each way (1080 / 150),
    still at least the pane's size, each sampled pixel where it was."""
    width, height = 1920, 1080
    x, y = numpy.meshgrid(numpy.arange(width), numpy.arange(height))
    pixels = numpy.dstack([x % 256, y % 256, (x // 256) * 16]).astype(numpy.uint8)
    surface = virtual.camera_surface(width, height, 'rgb8', width * 3, pixels.tobytes())
    assert surface.get_size() == (275, 155)
    assert surface.get_width() >= virtual.CAMERA_W and surface.get_height() >= virtual.CAMERA_H
    assert tuple(surface.get_at((100, 50)))[:3] == tuple(pixels[350, 700])
