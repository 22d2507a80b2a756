"""What the virtual panel's status lines say, kept true (pure, no ROS, no pygame).

:class:`PanelStatus` takes the Pirate Server's feedback and results, its
own word on ``/pirate/server_status`` (asked after every outcome and about
once a second), and the mission's lines, and gives the lines to show:

- a feedback of a goal that has ended (it can arrive after the result) is
  dropped: it must not overwrite how the goal ended;
- after every outcome the server state is the server's own answer
  ("Idle Partly Clamped (front partly, rear partly)"), not a guess from
  the last feedback; while the server is idle the line follows it;
- a manager that does not answer says so; one that answers again after a
  silence is a new manager: the outcome and the mission's ending from
  before it are dropped (nothing stale after a restart);
- a running goal's line says about how long it has left, from when it was
  sent and how long a PAB of its kind typically takes
  (pirate.supervisory.durations), or that it runs longer than that.

:func:`wrap` breaks a line into lines that fit a width, so nothing is
clipped at the window's edge.
"""

#: How many ended goals' ids are remembered (a late feedback is one of the last few).
ENDED_KEPT = 16
NO_NEWS = 'PAB server: no news yet'
NO_ANSWER = 'no answer from pirate_manager (restarting?)'


class PanelStatus(object):
    """The PAB line and the mission line, from the server's and the mission's news."""

    def __init__(self):
        self.running = ''       # the running goal's feedback line
        self.outcome = ''       # how the last goal ended
        self.server = ''        # the server's own state, from /pirate/server_status
        self.mission = ''       # the mission's line
        self._ended = []        # ids of goals that ended, newest last
        self._answered = None   # None: never asked; True / False: the last ask answered
        self._running_id = None  # the goal whose feedback is the running line
        self._sent = {}         # goal id -> (typical duration s, robot time s it was sent)

    def goal(self, goal_id, typical_s, sent_s):
        """Goal ``goal_id`` was sent at robot time ``sent_s``; a PAB of its kind takes about ``typical_s``."""
        self._sent = {goal_id: (typical_s, sent_s)}

    def feedback(self, goal_id, text):
        """A feedback line of goal ``goal_id``; False when dropped (the goal has ended)."""
        if goal_id in self._ended:
            return False
        self.running, self._running_id = text, goal_id
        return True

    def result(self, goal_id, text):
        """Goal ``goal_id`` ended: ``text`` says how. The server state is asked next."""
        self._ended = (self._ended + [goal_id])[-ENDED_KEPT:]
        self.running = ''
        self.outcome = text

    def server_status(self, active, state):
        """The server's answer (``active``, its state text), or ``state`` None when it gave
        none. Return True when a manager answers again after a silence (a restart)."""
        if state is None:
            self.server, self._answered = NO_ANSWER, False
            return False
        restarted = self._answered is False
        self._answered = True
        self.server = state
        if not active:
            self.running = ''
        if restarted:
            self.outcome = self.mission = ''
        return restarted

    def mission_line(self, text):
        self.mission = text

    def pab_line(self, now_s=None):
        """The PAB line: the running goal (with its time left at robot time
        ``now_s``), else the last outcome with the server's state."""
        news = self.running or self.outcome or NO_NEWS
        if self.running:
            return news + self._time_left(now_s)
        if not self.server:
            return news
        return '%s | Server: %s' % (news, self.server)

    def _time_left(self, now_s):
        sent = self._sent.get(self._running_id)
        if sent is None or now_s is None or not sent[0]:
            return ''
        return ' | ' + time_left(sent[0], now_s - sent[1])


def time_left(typical_s, elapsed_s):
    """How long a PAB that typically takes ``typical_s`` has left after ``elapsed_s`` (s), in words."""
    if elapsed_s <= typical_s:
        return 'about %.0f s left (typically %.0f s)' % (typical_s - elapsed_s, typical_s)
    return '%.0f s so far, longer than the typical %.0f s' % (elapsed_s, typical_s)


def control_labels(panel_map):
    """{channel: what the slider or knob moves in manual mode}, from the panel map's
    functions (pirate.panel.config.PanelConfig), shortened to fit under a control."""
    labels = {}
    for entry in panel_map.channels.values():
        if entry.action in ('setpoint', 'limit') and 'manual' in entry.modes:
            labels[entry.channel] = (entry.function.replace(' setpoint', '').replace('torque limit ', 'limit ')
                                     .replace('drive (wheels)', 'wheels'))
    return labels


#: Joints in the robot's order, front to rear, with their short names on the panel.
JOINT_WORDS = (('front_tilt', 'front'), ('bend_i', 'I'), ('bend_ii', 'II'), ('rotation', 'rot'),
               ('bend_iii', 'III'), ('bend_iv', 'IV'))


def robot_line(angles, odometry_mm, along_mm=None, leds=None):
    """The robot at a glance: joint angles {name: rad}, odometry (mm), the distance
    along the pipe (mm, a mission's estimate; None without one) and the LEDs
    {'front' | 'rear': setpoint counts, 0 = off}."""
    joints = ' '.join('%s %+.2f' % (word, angles[name]) for name, word in JOINT_WORDS if name in angles)
    where = 'odometry %.0f mm' % odometry_mm
    where += ', along the pipe %.0f mm' % along_mm if along_mm is not None else ', along the pipe: no mission'
    lights = ', '.join('%s %s' % (part, 'on (%d)' % value if value else 'off')
                       for part, value in sorted((leds or {}).items()))
    return 'Robot: joints (rad) %s | %s%s' % (joints, where, ' | LEDs ' + lights if lights else '')


def wrap(text, fits):
    """``text`` in lines each of which ``fits(line)`` (a width test, e.g. a font's
    size against the window), broken between words; a word too long alone is
    broken where it must."""
    lines, line = [], ''
    for word in text.split(' '):
        candidate = word if not line else line + ' ' + word
        if fits(candidate):
            line = candidate
            continue
        if line:
            lines.append(line)
        line = word
        while not fits(line) and len(line) > 1:
            cut = max(i for i in range(1, len(line) + 1) if fits(line[:i]) or i == 1)
            lines.append(line[:cut])
            line = line[cut:]
    if line or not lines:
        lines.append(line)
    return lines
