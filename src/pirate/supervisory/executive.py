"""Mission executive: runs a route's plan PAB by PAB, the operator in charge.

What a gas-network inspector expects of it:

- **per-step policy**: a PAB that aborts is retried up to N times (the
  mission's ``policy``, per PAB name, default in config/supervisory.yaml),
  re-establishing the clamp the step starts from first ("re-clamp and retry
  a bend"); then the mission stops safe. A goal cancelled by the operator
  is never retried; a refused goal is not either (retrying cannot help),
  except a junction PAB refused at its start, which a re-clamp may cure
  (the first such re-clamp of a step spends no retry: :class:`Tries`);
- **localisation**: every report moves the estimate along the map; every
  junction a PAB finds re-anchors it, and a junction where the map has none,
  or none where it has one, stops the mission (pirate.supervisory.localiser).
  A junction PAB searches only as far as the map's place plus the
  localiser's tolerance there (at most the plan's search): one that ends
  ``junction_missing`` there stops the mission in the safe hold before the
  robot takes a junction further on, naming where it looked;
- **autonomy levels** (as FlexBE's, set from the panel): ``full`` runs every
  step, ``confirm`` waits before each PAB for the operator's confirmation,
  ``manual`` only shows the plan. The level may change at any time; it
  applies from the next step;
- **pause / resume**: pause cancels the running goal (the server leaves the
  robot in its safe hold) and waits; resume re-clamps if the robot is no
  longer clamped and runs the same step again, a Drive only for what is
  left of it; a junction PAB paused (or aborted) after it sensed its
  junction is re-anchored there. Straight on through a T-joint it runs
  again only if its front V has not passed the junction (else the mission
  stops, the robot held: a crossing cannot be resumed). A turn whose front
  had turned into the new pipe is re-sent as it is, without a re-clamp: the
  junction PAB goes on from where the robot is, by what it senses and, once
  the rear came round, by the Pirate Server's record of the turn (half round
  the corner a Clamp Sideways would undo the turn); if the PAB refuses, the
  retry's re-clamp follows. Cancel always ends the mission.
- **the log**: a ``journal`` is told every event as it happens, each
  step's start and success with the localiser's state, so a mission whose
  executive died can be taken up from it (pirate.supervisory.resume): a new
  executive starts at its :data:`Entry`, the step that was running run as
  after a pause.

Pure: the robot is an object with ``run(step) -> Report`` (blocking until
the goal ends), ``cancel()`` (any thread) and ``clamped()`` (the server's
sensed state now: asked at resume time, not taken from the report of the
cancelled goal, since the robot may have settled since); the ROS edge
provides one over actionlib. Operator calls (:meth:`pause`, :meth:`resume`, :meth:`cancel`,
:meth:`confirm`, :meth:`set_level`) come from any thread.
"""
import collections
import math
import threading

from pirate.sequencer.junctions import is_turn
from pirate.supervisory import durations
from pirate.supervisory.localiser import MapMismatch, searched_mm

FULL, CONFIRM, MANUAL = 'full', 'confirm', 'manual'
LEVELS = (FULL, CONFIRM, MANUAL)

#: What one goal came to: status succeeded / aborted / preempted / rejected;
#: odometry (mm) at its end; where a junction PAB found its junction (mm of
#: odometry) or None; ``junction_missing`` when it searched and found none.
Report = collections.namedtuple('Report', 'status message odometry_mm junction_odometry_mm junction_missing')


def found_at(start_odometry_mm, found_mm):
    """The odometry (mm) where a junction PAB found its junction, for a
    :data:`Report`: the Pirate result's ``junction_odometry`` counts from the
    goal's start (``start_odometry_mm``, the robot's odometry when it was
    sent); None when it found none (NaN or None)."""
    if found_mm is None or math.isnan(found_mm) or start_odometry_mm is None:
        return None
    return start_odometry_mm + found_mm


#: Progress for the operator.
#: ``option`` and ``distance_mm`` name the PAB exactly (the panel blinks its button).
Progress = collections.namedtuple('Progress', 'step steps pab option distance_mm along_m time_left_s level '
                                              'state waiting_for')
#: How ``waiting_for`` begins when the executive waits for the operator.
WAIT_RESUME, WAIT_CONFIRM = 'resume', 'confirmation'
#: How the mission ended: succeeded / aborted / cancelled / mismatch / manual.
Outcome = collections.namedtuple('Outcome', 'status message log')
#: Where a mission taken up from its log goes on: ``step`` (0-based) runs
#: first; ``interrupted``: it had started when the executive died, so it
#: runs as after a pause (re-clamped if the robot is no longer clamped, a
#: Drive only for what is left); ``turn_begun``: a turn that may have
#: sensed its junction, re-sent as it is (pirate.supervisory.resume).
Entry = collections.namedtuple('Entry', 'step interrupted turn_begun')


def between_missions(text, next_level):
    """The operator's word when no mission runs: (ok, message, the level of
    the next mission whose goal names none). Here only ``level X`` means
    something (the panel's level buttons work before a mission); the ROS
    edge answers ``last`` and ``resume`` from the log itself."""
    words = text.strip().lower().split()
    if len(words) == 2 and words[0] == 'level' and words[1] in LEVELS:
        return True, 'autonomy level %s for the next mission' % words[1], words[1]
    return False, 'no mission is running', next_level


class Tries(object):
    """A step's retries (the mission's policy, per PAB) and its one free
    re-clamp: a junction PAB refused at its start because the drive up to
    the junction rolled the robot out of its clamp's region (bench/
    mission_sweep) is cured by a re-clamp; spending a retry on it left none
    for what can go wrong later in the turn."""

    def __init__(self, retries):
        self.left, self.free = retries, True

    def spend(self, refused_at_start):
        """Take one try (the free one for a refusal at the start); False when none is left."""
        if refused_at_start and self.free:
            self.free = False
            return True
        if self.left <= 0:
            return False
        self.left -= 1
        return True


class Stop(Exception):
    """The mission ends here: status and reason."""

    def __init__(self, status, message):
        Exception.__init__(self, message)
        self.status = status


class Executive(object):
    """Runs one plan; one instance per mission."""

    def __init__(self, route_plan, robot, localiser, settings, policy=None, level=FULL,
                 progress=None, out=print, journal=None, name='mission', goal=None, entry=None):
        if level not in LEVELS:
            raise ValueError('autonomy level %r is not one of %s' % (level, ', '.join(LEVELS)))
        self.plan, self.robot, self.localiser = route_plan, robot, localiser
        self.settings, self.policy = settings, dict(policy or {})
        self.level, self.log = level, []
        self._progress, self._out = progress or (lambda p: None), out
        #: ``journal(record)``: every event as it happens (pirate.supervisory.mission_log)
        self._journal, self.name = journal or (lambda record: None), name
        #: what the mission was asked (map, points, ...: the log's start record), and where it starts
        self.goal, self.entry = goal, entry or Entry(0, False, False)
        self._cond = threading.Condition()
        self._paused = self._cancelled = self._running = False
        self._confirmed = -1
        self.step_index, self.state, self.waiting_for = 0, 'ready', ''
        self.search = None      # the localiser's Search of the junction step that runs

    # --- operator side, any thread ----------------------------------------
    def pause(self, reason=''):
        """Hold the robot safe and wait for :meth:`resume`; ``reason`` goes
        to the log (e.g. the panel that disconnected)."""
        self._stop_running('pause' + (' (%s)' % reason if reason else ''), '_paused')

    def resume(self):
        """Go on with the step that was paused."""
        with self._cond:
            self._paused = False
            self._cond.notify_all()
        self._say('resume asked')

    def cancel(self):
        """End the mission: the running goal is cancelled, nothing else runs."""
        self._stop_running('cancel', '_cancelled')

    def _stop_running(self, word, flag):
        """Raise ``flag`` and cancel the goal running now, if any (the server
        leaves the robot in its safe hold)."""
        with self._cond:
            setattr(self, flag, True)
            running = self._running
            self._cond.notify_all()
        self._say('%s asked' % word)
        if running:
            self.robot.cancel()

    def confirm(self):
        """The operator confirms the step that waits (level ``confirm``)."""
        with self._cond:
            self._confirmed = self.step_index
            self._cond.notify_all()

    def set_level(self, level):
        """Change the autonomy level; applies from the next step."""
        if level not in LEVELS:
            raise ValueError('autonomy level %r is not one of %s' % (level, ', '.join(LEVELS)))
        with self._cond:
            self.level = level
            self._cond.notify_all()
        self._say('autonomy level: %s' % level)

    def command(self, text):
        """The operator's word as text (the MissionCommand service, the
        panel): (ok, message); an unknown word changes nothing."""
        words = text.strip().lower().split()
        simple = {'pause': self.pause, 'resume': self.resume, 'confirm': self.confirm, 'cancel': self.cancel}
        if len(words) > 1 and words[0] == 'pause':
            reason = text.strip().split(None, 1)[1]
            self.pause(reason)
            return True, 'pause (%s): done (step %d)' % (reason, self.step_index + 1)
        if len(words) == 1 and words[0] in simple:
            simple[words[0]]()
            return True, '%s: done (step %d, %s)' % (words[0], self.step_index + 1, self.state)
        if len(words) == 2 and words[0] == 'level':
            try:
                self.set_level(words[1])
            except ValueError as refused:
                return False, str(refused)
            return True, 'autonomy level %s from the next step' % words[1]
        return False, 'unknown command %r (pause [reason], resume, confirm, cancel, level full|confirm|manual)' % text

    # --- the mission thread -----------------------------------------------
    def run(self):
        """Run the plan to its :data:`Outcome`."""
        steps = self.plan.steps
        self.step_index = self.entry.step
        self._journal({'event': 'start', 'mission': self.name, 'steps': len(steps), 'level': self.level,
                       'goal': self.goal, 'first_step': self.step_index + 1, 'localiser': self.localiser.state()})
        if self.level == MANUAL:
            self._say('manual: the plan is shown, nothing runs')
            return self._end('manual', 'plan shown; nothing run (level manual)')
        try:
            while self.step_index < len(steps):
                self._step(steps[self.step_index])
                self.step_index += 1
        except Stop as stop:
            return self._end(stop.status, str(stop))
        return self._end('succeeded', '%d PABs, at %.0f mm' % (len(steps), self.localiser.along_m * 1000))

    def _step(self, step):
        """Run ``step`` between its records in the log: started (with the
        estimate then) and succeeded (with the estimate after)."""
        number, entry = self.step_index + 1, self.entry
        self._journal({'event': 'step', 'step': number, 'pab': step.pab, 'option': step.option,
                       'localiser': self.localiser.state()})
        if entry.interrupted and entry.step == self.step_index:
            self._run_step(step, True, entry.turn_begun)
        else:
            self._run_step(step)
        self._journal({'event': 'step_end', 'step': number, 'pab': step.pab, 'status': 'succeeded',
                       'localiser': self.localiser.state()})

    def _run_step(self, step, resuming=False, turn_begun=False):
        """``resuming``: the step had begun (paused, or its executive died),
        ``turn_begun``: a turn re-sent as it is."""
        tries = Tries(self._retries(step))
        while True:
            self._await_go(step)
            if resuming and not turn_begun and step.holds is not None and not self.robot.clamped():
                self._reclamp(step, 'resume')
            todo = self._remaining(step, turn_begun)
            if todo is None:
                self._not_running()
                return None
            report = self._goal(todo)
            if report.status == 'succeeded':
                if not (turn_begun and report.junction_odometry_mm is None):   # a resumed turn senses no junction
                    self._arrived(step, report)
                return self._after_turn(step, report)
            resuming = False
            if self._cancelled:
                raise Stop('cancelled', 'cancelled by the operator during step %d (%s)'
                           % (self.step_index + 1, step.pab))
            if report.status == 'preempted' and self._paused:
                resuming = True
                turn_begun = self._check_rerun(step, report, 'pause') or turn_begun
                continue
            if report.status == 'preempted':
                raise Stop('cancelled', 'step %d (%s) was cancelled outside the mission: %s'
                           % (self.step_index + 1, step.pab, report.message))
            if report.junction_missing:
                raise self._junction_missing()
            refused_at_start = report.status == 'rejected' and self._reclamp_may_help(step)
            if (report.status == 'rejected' and not refused_at_start) or not tries.spend(refused_at_start):
                raise Stop('aborted', 'step %d (%s) %s: %s' % (self.step_index + 1, step.pab, report.status,
                                                              report.message))
            turn_begun = self._check_rerun(step, report, 'abort') or turn_begun
            self._say('step %d (%s) %s: %s; retrying (%d left)'
                      % (self.step_index + 1, step.pab, report.status, report.message, tries.left))
            if report.status == 'rejected' or not turn_begun:
                self._reclamp(step, 'retry')

    @staticmethod
    def _reclamp_may_help(step):
        """A junction PAB refuses to start unless the robot holds the clamp it
        starts from within its straight region; the drive up to the junction
        may roll the robot out of it (bench/mission_sweep: clamped at 1.52 rad
        after the drive, refused). Re-clamping first, as a retry does, cures
        that; any other refusal comes back and then ends the mission."""
        return step.junction is not None and step.holds is not None

    def _check_rerun(self, step, report, why):
        """Before ``step`` runs again after a pause or an abort (``why``):
        True when it is a turn that had begun (its front had turned into the
        new pipe), to be re-sent as it is.

        A junction PAB that had sensed its junction re-anchors the estimate
        there. A turn's PAB goes on from where the robot senses it is
        (pirate.sequencer.pabs.junction, resuming a turn). Straight on, run
        again, it senses the junction again only while its front V has not
        passed it (moved less than the junction's length since); beyond that
        the crossing cannot be resumed (the junction PAB has no entry in the
        middle of a crossing, and a clamped robot driven on with a V over the
        hole stalled in the twin while its odometry counted on):
        :class:`Stop`, the robot held where it is."""
        if step.junction is None or report.junction_odometry_mm is None:
            return False
        self._arrived(step, report)
        if is_turn(step.junction.direction):
            self._say('  %s: the turn had begun (the front turned into the new pipe); step %d is sent again as it '
                      'is and goes on from where the robot is' % (step.junction.name, self.step_index + 1))
            return True
        moved_mm = abs(report.odometry_mm - report.junction_odometry_mm)
        length_mm = (step.junction.exit_m - step.junction.entry_m) * 1000.0
        if moved_mm > length_mm:
            raise Stop('aborted', '%s in step %d (%s %s) %.0f mm after sensing %s, more than its %.0f mm: the '
                       'crossing had begun and cannot be resumed; the robot is held where it is'
                       % (why, self.step_index + 1, step.pab, step.option, moved_mm, step.junction.name,
                          length_mm))
        self._say('  %s was sensed %.0f mm before the %s: step %d runs again from there'
                  % (step.junction.name, moved_mm, why, self.step_index + 1))
        return False

    def _await_go(self, step):
        """Wait while paused or unconfirmed; :class:`Stop` on cancel."""
        with self._cond:
            while not self._cancelled:
                if self._paused:
                    self._set_waiting('%s (paused)' % WAIT_RESUME)
                elif self.level == CONFIRM and self._confirmed != self.step_index:
                    self._set_waiting('%s of step %d (%s)' % (WAIT_CONFIRM, self.step_index + 1, step.pab))
                else:
                    self._set_waiting('')
                    self._running = True
                    return
                self._cond.wait()
        raise Stop('cancelled', 'cancelled by the operator before step %d (%s)' % (self.step_index + 1, step.pab))

    def _set_waiting(self, what):
        changed = what != self.waiting_for
        self.waiting_for = what
        self.state = 'waiting' if what else 'running'
        if changed:
            self._publish(self.plan.steps[self.step_index])
            if what:
                self._say('waiting for %s' % what)

    def _goal(self, step):
        """Run one goal and move the estimate by its odometry."""
        self._say('step %d/%d: %s%s%s, %s' % (
            self.step_index + 1, len(self.plan.steps), step.pab, ' %s' % step.option if step.option else '',
            ' %+.0f mm' % step.distance_mm if step.distance_mm else '', step.note))
        self._publish(step)
        try:
            report = self.robot.run(step)
        finally:
            with self._cond:
                self._running = False
        if report.odometry_mm is not None:
            self.localiser.update(report.odometry_mm)
        self._say('  %s: %s (at %.0f mm)' % (report.status, report.message, self.localiser.along_m * 1000))
        return report

    def _after_turn(self, step, report):
        """A turn taken: the estimate re-anchored where the turn left the
        robot (its wheels slip round the corner, its odometry does not say)."""
        if step.junction is not None and is_turn(step.junction.direction):
            self.localiser.turn_taken(step.end_m, report.odometry_mm)
            self._say('  %s taken: re-anchored at %.0f mm, where a turn ends' % (step.junction.name,
                                                                               step.end_m * 1000))

    def _arrived(self, step, report):
        if step.junction is None:
            return
        if report.junction_odometry_mm is None:
            raise self._junction_missing()
        try:
            mapped = self.localiser.junction_found(step.junction, report.junction_odometry_mm,
                                                   1 if step.distance_mm > 0 else -1)
        except MapMismatch as mismatch:
            raise Stop('mismatch', str(mismatch))
        self._say('  %s found where the map has it: re-anchored at %.0f mm' % (step.junction.name, mapped * 1000))
        self.localiser.update(report.odometry_mm)

    def _reclamp(self, step, why):
        """Before a retry or a resume: the clamp the step starts from."""
        if step.holds is None:
            return
        clamp = step._replace(pab=step.holds.pab, option=step.holds.side, distance_mm=0.0, junction=None,
                              note='re-clamp before the %s of step %d' % (why, self.step_index + 1))
        report = self._goal(clamp)
        if report.status != 'succeeded':
            raise Stop('aborted', 're-clamp before the %s of step %d failed: %s'
                       % (why, self.step_index + 1, report.message))

    def _not_running(self):
        with self._cond:
            self._running = False

    def _remaining(self, step, turn_begun=False):
        """A Drive goes from where the robot is estimated to be to the step's
        end: only what is left of it when resumed or retried (None: nothing).
        A junction step searches as far as the map lets it (:meth:`_bounded`),
        but a turn that had begun is sent as planned: it goes on from where
        the robot is and searches nothing."""
        if step.junction is not None and not turn_begun:
            return self._bounded(step)
        if step.pab != 'DRIVE':
            return step
        left_mm = (step.end_m - self.localiser.along_m) * 1000.0
        return step._replace(distance_mm=left_mm) if abs(left_mm) >= self.settings['min_drive_mm'] else None

    def _bounded(self, step):
        """``step`` searching only as far as a junction sensed there would
        still be the map's (pirate.supervisory.localiser Search), at most the
        plan's search distance; :class:`Stop` when the estimate is already
        beyond it (nothing sent)."""
        sign = 1 if step.distance_mm > 0 else -1
        self.search = self.localiser.search(step.junction, sign, abs(step.distance_mm))
        distance_mm = searched_mm(self.search)
        if distance_mm < self.settings['min_drive_mm']:
            self._not_running()
            raise self._junction_missing()
        return step._replace(distance_mm=sign * distance_mm)

    def _junction_missing(self):
        """The :class:`Stop` of a junction step whose junction was not where
        the map has it: where it was looked for (the last :attr:`search`)."""
        return Stop('mismatch', '%s; the robot is held where it is'
                    % self.localiser.junction_missing(self.search))

    def _retries(self, step):
        default = self.policy.get('default', self.settings['policy'])
        return int(self.policy.get(step.pab, default).get('retries', 0))

    # --- telling the operator ---------------------------------------------
    def time_left_s(self):
        """Rough time left: each remaining PAB's typical duration, drives by speed."""
        return sum(durations.typical_s(step.pab, step.distance_mm, step.speed_mm_s, self.settings['typical_s'])
                   for step in self.plan.steps[self.step_index:])

    def _publish(self, step):
        self._progress(Progress(self.step_index + 1, len(self.plan.steps), step.pab, step.option or '',
                                step.distance_mm, self.localiser.along_m, self.time_left_s(), self.level,
                                self.state, self.waiting_for))

    def _say(self, text):
        self.log.append(text)
        self._journal({'event': 'say', 'step': min(self.step_index + 1, len(self.plan.steps)), 'text': text})
        self._out(text)

    def _end(self, status, message):
        self.state = status
        self._say('mission %s: %s' % (status, message))
        self._journal({'event': 'end', 'status': status, 'message': message})
        return Outcome(status, message, list(self.log))
