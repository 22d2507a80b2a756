"""An on-screen nanoKONTROL2: layout, hit-testing, state and drawing.

It sends the same (channel, value) events as the hardware panel in its
default CC mode (SPEC 5) and shows the LEDs the Mapper lights, so the stack
can be driven on any laptop. No ROS here: :class:`VirtualPanel` turns pygame
events into (channel, value) pairs and draws its state on a surface; the
node (pirate.panel.virtual_node) moves those to and from the topics. Tests
synthesise pygame events and read pixels, headless (SDL_VIDEODRIVER=dummy).

Keyboard (strip = the selected channel strip, keys 1-8 select it):
  Up/Down slider +-4, PgUp/PgDn slider +-16, Left/Right knob -+4,
  s / m / r the strip's S / M / R button, p Play, space Stop, w Rewind,
  f fast forward, o Record, e marker Set (hold it), , and . Track < and >,
  c Cycle, [ and ] marker < and >.
Mouse: click buttons; drag sliders and knobs (vertically); wheel over a
slider or knob nudges it.
"""
import collections
import math
import os

import numpy

os.environ.setdefault('PYGAME_HIDE_SUPPORT_PROMPT', '1')
import pygame  # noqa: E402

from pirate.panel.status import wrap  # noqa: E402

STRIPS = 8
SLIDER_BASE, KNOB_BASE, S_BASE, M_BASE, R_BASE = 0, 16, 32, 48, 64
MIDI_MAX = 127
PRESSED, RELEASED = 127, 0

#: Transport and track buttons: channel -> (label, column, row, key).
TRANSPORT = collections.OrderedDict([
    (58, ('TRACK <', 0, 0, pygame.K_COMMA)), (59, ('TRACK >', 1, 0, pygame.K_PERIOD)),
    (46, ('CYCLE', 0, 1, pygame.K_c)), (60, ('SET', 2, 1, pygame.K_e)),
    (61, ('MARKER <', 3, 1, pygame.K_LEFTBRACKET)), (62, ('MARKER >', 4, 1, pygame.K_RIGHTBRACKET)),
    (43, ('<< REW', 0, 2, pygame.K_w)), (44, ('FF >>', 1, 2, pygame.K_f)),
    (42, ('STOP', 2, 2, pygame.K_SPACE)), (41, ('PLAY', 3, 2, pygame.K_p)),
    (45, ('REC', 4, 2, pygame.K_o)),
])
STRIP_KEYS = {pygame.K_s: S_BASE, pygame.K_m: M_BASE, pygame.K_r: R_BASE}
#: Channel of the operation-mode button: its LED on means PAB mode (SPEC 5).
OPERATION_MODE_BUTTON, PLAY_BUTTON = 43, 41

#: Status lines: mode, PAB, the panel's word, the mission, the robot, each wrapped to the window.
STATUS_LINES, STATUS_LINE_H = 7, 18
STATUS_H = 10 + STATUS_LINES * STATUS_LINE_H
PANEL_W, HEIGHT = 940, STATUS_H + 300   # the controls, and the manual labels under the sliders
#: The cameras' pane right of the panel: each camera's newest image (160 x 120
#: from the twin, scaled) under its name, front above rear.
CAMERAS = ('front', 'rear')
CAMERA_W, CAMERA_H, CAMERA_LABEL_H = 200, 150, 22
WIDTH = PANEL_W + CAMERA_W + 24
#: sensor_msgs/Image encodings the pane shows: bytes per pixel.
IMAGE_ENCODINGS = {'rgb8': 3, 'bgr8': 3, 'mono8': 1}
STRIP_W = 64      # px between two channel strips
BODY, PANEL_EDGE, TEXT = (38, 38, 42), (90, 90, 96), (225, 225, 225)
BUTTON_OFF, BUTTON_LIT, SLOT, THUMB = (70, 70, 76), (235, 40, 40), (15, 15, 15), (200, 200, 205)
KNOB, KNOB_MARK = (120, 120, 128), (250, 250, 250)
#: Colour depth of the panel's surfaces: true colour on every display
#: (pygame 1.9.6 with no display, SDL's dummy driver, gives 8 bits).
DEPTH_BITS = 32
#: Rounded button corners where pygame draws them (2.0 on; 1.9.6 draws square).
ROUNDED = {'border_radius': 4} if pygame.version.vernum[0] >= 2 else {}
#: Mouse buttons the wheel arrives as (pygame 1.9.6 only so; 2.x also so):
#: button -> steps up.
WHEEL_BUTTONS = {4: 1, 5: -1}

#: Where the PAB buttons are listed (screen px): under the transport buttons.
PAB_LIST_X, PAB_LIST_Y, PAB_LIST_COLUMN_W = 14, STATUS_H + 188, 212

Control = collections.namedtuple('Control', 'kind channel label rect')


def camera_surface(width, height, encoding, step, data):
    """A pygame Surface of a sensor_msgs/Image's fields (rgb8, bgr8 or
    mono8), every k-th pixel of an image k or more times the pane's size
    each way (a grabber's 1920 x 1080: 9 x 7 fewer pixels to convert);
    ValueError saying what is wrong with any other."""
    if encoding not in IMAGE_ENCODINGS:
        raise ValueError('a %s image is not shown (%s)' % (encoding or 'no-encoding', ', '.join(IMAGE_ENCODINGS)))
    channels = IMAGE_ENCODINGS[encoding]
    if width <= 0 or height <= 0 or step < width * channels or len(data) < step * height:
        raise ValueError('a %d x %d %s image with rows of %d bytes needs %d bytes, not %d'
                         % (width, height, encoding, step, step * height, len(data)))
    every = max(1, min(width // CAMERA_W, height // CAMERA_H))
    rows = numpy.frombuffer(bytes(data[:step * height]), numpy.uint8).reshape(height, step)
    pixels = rows[::every, :width * channels].reshape(-1, width, channels)[:, ::every]
    if encoding == 'bgr8':
        pixels = pixels[:, :, ::-1]
    elif channels == 1:
        pixels = numpy.repeat(pixels, 3, axis=2)
    return pygame.image.fromstring(numpy.ascontiguousarray(pixels).tobytes(), pixels.shape[1::-1], 'RGB')


def _layout():
    """Every control of the panel with its screen rectangle."""
    controls = []
    bw, bh = 70, 26
    for channel, (label, col, row, _key) in TRANSPORT.items():
        rect = pygame.Rect(14 + col * (bw + 6), STATUS_H + 30 + row * 60, bw, bh)
        controls.append(Control('button', channel, label, rect))
    x0 = 420
    for i in range(STRIPS):
        x = x0 + i * STRIP_W
        controls.append(Control('knob', KNOB_BASE + i, 'K%d' % (i + 1),
                                pygame.Rect(x + 14, STATUS_H + 12, 36, 36)))
        for j, (base, name) in enumerate(((S_BASE, 'S'), (M_BASE, 'M'), (R_BASE, 'R'))):
            controls.append(Control('button', base + i, name,
                                    pygame.Rect(x + 2, STATUS_H + 80 + j * 46, 24, 20)))
        controls.append(Control('slider', SLIDER_BASE + i, str(i + 1),
                                pygame.Rect(x + 34, STATUS_H + 66, 20, 190)))
    return controls


class VirtualPanel(object):
    """State of the virtual panel and the events it produces."""

    def __init__(self):
        self.controls = _layout()
        self._by_channel = {c.channel: c for c in self.controls}
        self.values = {c.channel: (63 if c.kind == 'slider' else 0)
                       for c in self.controls if c.kind != 'button'}
        self.leds = {}
        self.selected = 0
        self.pab_text = 'PAB server: no news yet'
        self.operator_text = ''     # the Mapper's last message (refusals, results)
        self.mission_text = ''      # the mission executive's step, level and what it waits for
        self.pab_list = []          # one line per PAB button (pirate.panel.config.pab_buttons)
        self.mission_labels = {}    # channel -> its PAB-mode (mission) label (mission_buttons.labels)
        self.manual_labels = {}     # channel -> what a slider or knob moves in manual mode (status.control_labels)
        self.robot_text = ''        # joints, odometry, distance along the pipe, LEDs (status.robot_line)
        self.cameras = {camera: 'no image yet' for camera in CAMERAS}   # a Surface, or why there is none
        self._dragging = None
        self._held = None
        self._font = None
        self._small_font = None

    def control(self, channel):
        return self._by_channel[channel]

    def hit(self, pos):
        """The control under screen position ``pos``, or None."""
        for control in self.controls:
            if control.rect.collidepoint(pos):
                return control
        return None

    # --- input ---------------------------------------------------------------

    def handle_event(self, event):
        """Return the list of (channel, value) the event produces."""
        if event.type == pygame.MOUSEBUTTONDOWN and event.button == 1:
            control = self.hit(event.pos)
            if control is None:
                return []
            if control.kind == 'button':
                self._held = control.channel
                return [(control.channel, PRESSED)]
            self._dragging = control
            return self._drag_to(control, event.pos)
        if event.type == pygame.MOUSEBUTTONUP and event.button == 1:
            self._dragging = None
            if self._held is not None:
                channel, self._held = self._held, None
                return [(channel, RELEASED)]
            return []
        if event.type == pygame.MOUSEMOTION and self._dragging is not None:
            return self._drag_to(self._dragging, event.pos)
        if event.type == pygame.MOUSEBUTTONDOWN and event.button in WHEEL_BUTTONS:
            control = self.hit(event.pos)
            if control is not None and control.kind != 'button':
                return self._set(control.channel, self.values[control.channel] + 2 * WHEEL_BUTTONS[event.button])
            return []
        if event.type in (pygame.KEYDOWN, pygame.KEYUP):
            return self._key(event)
        return []

    def _drag_to(self, control, pos):
        rect = control.rect
        if control.kind == 'slider':
            fraction = (rect.bottom - pos[1]) / float(rect.height)
        else:   # knob: the vertical position across a band around the knob
            fraction = (rect.centery + 50 - pos[1]) / 100.0
        return self._set(control.channel, int(round(fraction * MIDI_MAX)))

    def _set(self, channel, value):
        value = max(0, min(MIDI_MAX, value))
        if self.values.get(channel) == value:
            return []
        self.values[channel] = value
        return [(channel, value)]

    def _key(self, event):
        down = event.type == pygame.KEYDOWN
        value = PRESSED if down else RELEASED
        for channel, (_label, _c, _r, key) in TRANSPORT.items():
            if event.key == key:
                return [(channel, value)]
        if event.key in STRIP_KEYS:
            return [(STRIP_KEYS[event.key] + self.selected, value)]
        if not down:
            return []
        if pygame.K_1 <= event.key <= pygame.K_8:
            self.selected = event.key - pygame.K_1
            return []
        steps = {pygame.K_UP: (SLIDER_BASE, 4), pygame.K_DOWN: (SLIDER_BASE, -4),
                 pygame.K_PAGEUP: (SLIDER_BASE, 16), pygame.K_PAGEDOWN: (SLIDER_BASE, -16),
                 pygame.K_RIGHT: (KNOB_BASE, 4), pygame.K_LEFT: (KNOB_BASE, -4)}
        if event.key in steps:
            base, step = steps[event.key]
            channel = base + self.selected
            return self._set(channel, self.values[channel] + step)
        return []

    # --- output ----------------------------------------------------------------

    def set_led(self, button, on):
        """Light or clear a button LED (a MidiOutput from the Mapper)."""
        self.leds[button] = bool(on)

    @property
    def operation_mode(self):
        return 'PAB' if self.leds.get(OPERATION_MODE_BUTTON) else 'MANUAL'

    def status_lines(self):
        run = 'playing' if self.leds.get(PLAY_BUTTON) else 'stopped'
        return ['Operation mode: %s   (%s)   strip %d selected'
                % (self.operation_mode, run, self.selected + 1), self.pab_text,
                'Panel: %s' % self.operator_text if self.operator_text else '',
                'Mission: %s' % self.mission_text if self.mission_text else '',
                self.robot_text]

    def wrapped_status(self):
        """The status lines wrapped to the window (nothing clipped at its edge), at most STATUS_LINES."""
        lines = [part for line in self.status_lines() if line for part in wrap(line, self._fits_status)]
        return lines[:STATUS_LINES]

    def draw(self, surface):
        """Draw the whole panel on ``surface`` (WIDTH x HEIGHT)."""
        if self._font is None:
            pygame.font.init()
            self._font = pygame.font.Font(None, 20)
            self._small_font = pygame.font.Font(None, 15)
        surface.fill(BODY)
        pygame.draw.rect(surface, PANEL_EDGE, surface.get_rect(), 3)
        pygame.draw.line(surface, PANEL_EDGE, (0, STATUS_H), (PANEL_W, STATUS_H), 2)
        pygame.draw.line(surface, PANEL_EDGE, (PANEL_W, 0), (PANEL_W, HEIGHT), 2)
        self._draw_status(surface)
        for control in self.controls:
            getattr(self, '_draw_' + control.kind)(surface, control)
        self._draw_pab_list(surface)
        self._draw_manual_labels(surface)
        for i, camera in enumerate(CAMERAS):
            self._draw_camera(surface, camera, self.camera_rect(i))

    @staticmethod
    def camera_rect(i):
        """Where camera ``i`` of :data:`CAMERAS` is shown (screen px)."""
        return pygame.Rect(PANEL_W + 12, 8 + CAMERA_LABEL_H + i * (CAMERA_H + CAMERA_LABEL_H + 12),
                           CAMERA_W, CAMERA_H)

    def _draw_camera(self, surface, camera, rect):
        """The camera's newest image scaled into ``rect``, or why there is none."""
        surface.blit(self._font.render('%s camera' % camera, True, TEXT), (rect.x, rect.y - CAMERA_LABEL_H + 4))
        shown = self.cameras.get(camera)
        if isinstance(shown, pygame.Surface):
            surface.blit(pygame.transform.scale(shown, rect.size), rect.topleft)
            return
        pygame.draw.rect(surface, SLOT, rect)
        for i, line in enumerate(wrap(str(shown), lambda text: self._small_font.size(text)[0] <= CAMERA_W - 8)[:4]):
            surface.blit(self._small_font.render(line, True, TEXT), (rect.x + 4, rect.y + 4 + i * 12))

    def _fits_status(self, text):
        return self._font.size(text)[0] <= PANEL_W - 28

    def _draw_status(self, surface):
        for i, line in enumerate(self.wrapped_status()):
            surface.blit(self._font.render(line, True, TEXT), (14, 8 + i * STATUS_LINE_H))

    def _draw_manual_labels(self, surface):
        """In manual mode, what each slider and knob moves (the panel map's words), under it in
        at most two lines as wide as a strip."""
        if self.operation_mode != 'MANUAL':
            return
        fits = lambda text: self._small_font.size(text)[0] <= STRIP_W - 4     # noqa: E731
        for control in self.controls:
            if control.channel in self.manual_labels and control.kind in ('slider', 'knob'):
                top = control.rect.bottom + (20 if control.kind == 'slider' else 5)
                for i, line in enumerate(wrap(self.manual_labels[control.channel], fits)[:2]):
                    image = self._small_font.render(line, True, TEXT)
                    surface.blit(image, image.get_rect(midtop=(control.rect.centerx, top + i * 10)))

    def _draw_pab_list(self, surface):
        """The PAB buttons, in two columns under the transport buttons."""
        per_column = (len(self.pab_list) + 1) // 2
        for i, line in enumerate(self.pab_list):
            x, y = PAB_LIST_X + (i // per_column) * PAB_LIST_COLUMN_W, PAB_LIST_Y + (i % per_column) * 13
            surface.blit(self._small_font.render(line, True, TEXT), (x, y))

    def _label(self, surface, text, center):
        image = self._font.render(text, True, TEXT)
        surface.blit(image, image.get_rect(center=center))

    def _small_label(self, surface, text, center):
        """A small button's label, in the small font: the M row's mission jobs clear the sliders' thumbs."""
        image = self._small_font.render(text, True, TEXT)
        surface.blit(image, image.get_rect(center=center))

    def label(self, control):
        """What a button reads now: in PAB mode a mission button reads its
        mission job (the M row: confirm, pause, resume, levels), else its name."""
        if self.operation_mode == 'PAB' and control.channel in self.mission_labels:
            return self.mission_labels[control.channel]
        return control.label

    def _draw_button(self, surface, control):
        colour = BUTTON_LIT if self.leds.get(control.channel) else BUTTON_OFF
        pygame.draw.rect(surface, colour, control.rect, **ROUNDED)
        if control.rect.width > 30:
            self._label(surface, self.label(control), control.rect.center)
        else:
            self._small_label(surface, self.label(control), (control.rect.centerx, control.rect.bottom + 8))

    def _draw_slider(self, surface, control):
        rect = control.rect
        pygame.draw.rect(surface, SLOT, rect.inflate(-12, 0))
        y = rect.bottom - int(round(self.values[control.channel] / float(MIDI_MAX) * rect.height))
        pygame.draw.rect(surface, THUMB, pygame.Rect(rect.x, y - 6, rect.width, 12))
        self._label(surface, control.label, (rect.centerx, rect.bottom + 12))

    def _draw_knob(self, surface, control):
        rect = control.rect
        radius = rect.width // 2
        pygame.draw.circle(surface, KNOB, rect.center, radius)
        # 0..127 sweeps from 7 o'clock to 5 o'clock, like the real knob.
        angle = math.radians(225 - 270 * self.values[control.channel] / float(MIDI_MAX))
        end = (rect.centerx + int(radius * math.cos(angle)),
               rect.centery - int(radius * math.sin(angle)))
        pygame.draw.line(surface, KNOB_MARK, rect.center, end, 3)
