"""Motion primitives (report 4.7.2, 5.9; SPEC 7) and the safe hold.

Basic primitives write a message and return. Advanced ones write, then wait
on the robot state for their guard (event-driven, :mod:`pirate.state.feed`), with
a timeout and an immediate stop on cancel. Guards and setpoints come from
:class:`pirate.sequencer.guards.Guards`; limits are those of :mod:`pirate.robot.safety`,
enforced inside the Setpoint/Control classes. Pure Python.

Every write happens in :meth:`MotionPrimitives.writing`: under the arrays'
wire lock and only while the goal is neither cancelled nor without
feedback, so a Stop's safe hold is always the last thing a cancelled PAB
puts on the wire (the hold is atomic: pirate.robot.hold).
"""
import contextlib

from pirate.robot import safety, tables, units
from pirate.robot.hold import safe_hold
from pirate.sequencer import clamp_state
from pirate.state.feed import SensorFrozen, TimedOut

#: Suffix of a guard row for the robot lying on a side (config/guards_<mm>.yaml).
SIDEWAYS = clamp_state.SIDEWAYS

class Refused(ValueError):
    """A primitive asked for something outside the robot's limits."""


class BendProgress(object):
    """Bends driven open must move (``settings``: config/sequencer.yaml
    ``unclamp``): a bend angle or its spring, every ``no_progress_s`` of robot
    time. Where something holds them (a robot cancelled half round a junction,
    its modules against the walls) the unclamp ends blocked at once instead of
    pushing at the unclamp torque until the primitive timeout."""

    def __init__(self, settings, joints, what):
        self.window_s = settings['no_progress_s']
        self.min_rad, self.min_mnm = settings['no_progress_rad'], settings['no_progress_mnm']
        self.joints, self.what = joints, what
        self.mark = None

    def check(self, view):
        """False while the bends move (the guard is not reached); TimedOut once blocked."""
        angles = [view.angles[j] for j in self.joints]
        efforts = [(view.efforts or {}).get(j, 0.0) for j in self.joints]
        if self.mark is None or self._moved(angles, efforts):
            self.mark = (view.stamp, angles, efforts)
        elif view.stamp - self.mark[0] > self.window_s:
            raise TimedOut('%s blocked: %s stood still for %.1f s without opening (something holds them: '
                           'the walls of a junction?)' % (self.what, ', '.join(
                               '%s %.2f rad' % (j, a) for j, a in zip(self.joints, angles)), self.window_s))
        return False

    def _moved(self, angles, efforts):
        _, mark_angles, mark_efforts = self.mark
        return (any(abs(a - m) >= self.min_rad for a, m in zip(angles, mark_angles))
                or any(abs(e - m) >= self.min_mnm for e, m in zip(efforts, mark_efforts)))


#: The bends a frozen sensor is looked for on: a series spring between motor
#: and joint, so a driven bend moves its angle or its spring, even against a wall.
SPRING_BENDS = tuple(j.name for j in tables.JOINTS if j.has_spring)
_BOARD = {j.name: j.board for j in tables.JOINTS}
#: A torque-mode bend this far from its setpoint (mNm, plus a share of the
#: setpoint: what the motor needs to lift the spring's own load, 7 % in the
#: twin) is driven: its torque loop turns the motor at a tenth of full duty or
#: more (twin: 3 duty per count, 1 count about 1 mNm).
FROZEN_DEMAND_MNM = 10.0
FROZEN_DEMAND_SHARE = 0.1
#: mNm of spring a torque setpoint count comes to at rest: the twin's board
#: loop holds its spring at the setpoint's counts (about 1 mNm each); the
#: report's clamps peak at about 400 mNm for 256 (the fast fake robot's
#: 1.5625). Which the PICOs do is not measured, so a bend at either is at rest.
REST_MNM_PER_COUNT = (None, 400.0 / 256.0)
#: Driven for this long (robot s) with its angle and spring within
#: FROZEN_STILL of where they were, a bend's sensor is frozen. At a tenth of
#: full duty the worm turns 0.031 rad/s (0.311 rad/s no-load): in 0.5 s
#: 0.016 rad, 10 angle counts or 37 mNm on the spring; one Mega cycle more,
#: so a board that stops answering (its last readings held, silent after
#: 0.35-0.45 s on a clean bus) is named silent first; measurements.md#frozen-sensor.
FROZEN_WINDOW_S = 0.6
#: Still: less than 2 counts of either sensor (rad of angle, mNm of spring).
FROZEN_STILL_RAD, FROZEN_STILL_MNM = 2 * units.encoder_to_rad(1), 2.0


class FrozenJoints(object):
    """Bends driven by their torque loop whose readings stand still.

    ``demand(joint, view)`` -> mNm the joint's loop is driving for now (0
    when it is not driven). :meth:`check` raises :class:`SensorFrozen`
    naming the joint once it has been driven :data:`FROZEN_WINDOW_S`
    without its angle or spring moving; a joint that moves, or stops being
    driven, starts a new window.
    """

    def __init__(self, demand, joints=SPRING_BENDS, window_s=FROZEN_WINDOW_S):
        self.demand, self.joints, self.window_s = demand, joints, window_s
        self._marks = {}            # joint -> (stamp, angle, effort) when it was last seen moving
        self._stamp = None

    def reset(self):
        """A new goal: no joint is being watched."""
        self._marks, self._stamp = {}, None

    def check(self, view):
        """Raise SensorFrozen for a bend driven but still; None otherwise."""
        if view.stamp == self._stamp or view.efforts is None:
            return
        self._stamp = view.stamp
        for joint in self.joints:
            self._check_joint(joint, view)

    def _check_joint(self, joint, view):
        if joint not in view.angles or _BOARD[joint] in view.missed_boards:
            return                  # not answering: its silence is the state's to tell
        angle, effort = view.angles[joint], view.efforts.get(joint, 0.0)
        mark = self._marks.get(joint)
        if not self.demand(joint, view):
            self._marks.pop(joint, None)
        elif mark is None or abs(angle - mark[1]) >= FROZEN_STILL_RAD or abs(effort - mark[2]) >= FROZEN_STILL_MNM:
            self._marks[joint] = (view.stamp, angle, effort)
        elif view.stamp - mark[0] > self.window_s:
            raise SensorFrozen('%s reads frozen: driven %.0f mNm from its torque setpoint for %.1f s, its angle '
                               '(%.3f rad) and spring (%.0f mNm) did not move (sensor or its board stuck)'
                               % (joint, self.demand(joint, view), view.stamp - mark[0], angle, effort))


def report_kind(kind):
    """The report's primitive for guard row ``kind``: a ``*_sideways`` row is
    the same primitive with the guards of a robot lying on a side."""
    return kind[:-len(SIDEWAYS)] if kind.endswith(SIDEWAYS) else kind


def clamp_name(kind, part):
    """Primitive name as the report's tables write it, e.g. 'clamp rear custom'."""
    kind = report_kind(kind)
    if kind == 'clamp':
        return 'clamp %s' % part
    return 'clamp %s custom%s' % (part, ' first' if kind.endswith('_first') else '')


class MotionPrimitives(object):
    """The robot's motion vocabulary, over shared Setpoint/Control/Limit."""

    def __init__(self, setpoint, control, limit, feed, notify=None):
        self.setpoint = setpoint
        self.control = control
        self.limit = limit
        self.feed = feed
        self.guards = None
        self.executed = []          # names of advanced primitives, in order
        self.notify = notify or (lambda primitive, guard: None)
        self.frozen = FrozenJoints(self.torque_demand)
        feed.watch(self.frozen.check)

    def torque_demand(self, joint, view):
        """mNm bend ``joint``'s torque loop is driving for, or 0: its setpoint
        (within its torque limit) minus its spring, when that is more than
        the loop holds at rest (:data:`FROZEN_DEMAND_MNM`)."""
        if self.control.mode_of(joint) != 'torque':
            return 0.0
        limit = self.limit.get(joint) if self.limit is not None else safety.NO_LIMIT
        counts = max(-limit, min(limit, self.setpoint.get(joint)))
        effort = view.efforts.get(joint, 0.0)
        if self._holds_a_wall(counts, effort):
            return 0.0
        errors = [abs((units.spring_to_mnm(counts) if scale is None else scale * counts) - effort)
                  for scale in REST_MNM_PER_COUNT]
        error = min(errors)
        return error if error > FROZEN_DEMAND_MNM + FROZEN_DEMAND_SHARE * abs(units.spring_to_mnm(counts)) else 0.0

    def _holds_a_wall(self, counts, effort):
        """A bend whose spring already pushes the way its setpoint drives it
        with a clamp's effort (``spring_clamp_mnm``) presses a wall: where its
        motor reaches its stall short of the setpoint it stands still by
        physics, not because a sensor froze (twin, a robot drawn with a weak
        bend motor: a rear clamp held at 220 mNm for 256 counts)."""
        if self.guards is None or not counts:
            return False
        return effort * (1 if counts > 0 else -1) >= clamp_state.spring_clamp_mnm(self.guards)

    def use(self, guards):
        """Work with the guards of the goal's pipe diameter."""
        self.guards = guards
        self.executed = []
        self.frozen.reset()

    @contextlib.contextmanager
    def writing(self):
        """Write under the wire lock, or raise Cancelled/FeedbackLost instead.

        The check and the writes are one step for the safe hold, which takes
        the same lock: a hold never lands between them.
        """
        with self.control.wire_lock:
            self.feed.check()
            yield

    # --- basic ------------------------------------------------------------
    def move_module(self, joint, counts):
        """Setpoint for the front module or a bend module (counts)."""
        with self.writing():
            self.setpoint.set(joint, counts)

    def change_control_mode(self, joint, mode):
        """Control mode of one motor; goes out at once if it changed."""
        with self.writing():
            self.control.set_mode(joint, mode)

    def drive_at_velocity(self, mm_s):
        """Wheels at ``mm_s`` (signed); refused above the robot's maximum."""
        if not safety.drive_speed_ok(mm_s):
            raise Refused('drive speed %.1f mm/s beyond %.0f mm/s' % (mm_s, safety.DRIVE_MAX_MM_S))
        with self.writing():
            self.control.set_mode('wheels', 'velocity')
            self.setpoint.set('wheels', units.mm_s_to_wheel_counts(mm_s))

    # --- advanced ---------------------------------------------------------
    def wait_for(self, name, guard, text, timeout=None, stood=None):
        """Run primitive ``name``: announce it, wait for ``guard``, announce the end.

        ``timeout`` defaults to the configured primitive timeout (robot time);
        ``stood(view)``, given, says what the guard read when it timed out.
        """
        self.executed.append(name)
        self.notify(name, text)
        try:
            view = self.feed.wait_until(guard, timeout or self.guards.primitive_timeout,
                                        '%s: %s' % (name, text))
        except TimedOut as late:
            last = self.feed.latest()
            if stood is None or last is None:
                raise
            raise TimedOut('%s: %s' % (late, stood(last))) from late
        self.notify('', '%s reached %s' % (name, text))
        return view

    def follow(self, name, act, done, text, timeout):
        """Run primitive ``name``: call ``act(view)`` on each new robot state
        until ``done(view)`` (a closed loop the PICO boards do not run, e.g.
        the front tilt following the bends while steering into a new pipe).
        Raises TimedOut after ``timeout`` s of robot time."""
        self.executed.append(name)
        self.notify(name, text)
        view = self.feed.latest()
        end = view.stamp + timeout
        while not done(view):
            act(view)
            seen = view.stamp
            view = self.feed.wait_until(lambda v: v.stamp > seen, max(end - seen, 0.0),
                                        '%s: %s' % (name, text))
            if view.stamp >= end:
                raise TimedOut('%s: %s not reached within %.1f s' % (name, text, timeout))
        self.notify('', '%s reached %s' % (name, text))
        return view

    def clamp(self, part, kind='clamp'):
        """Clamp ``part`` ('front'/'rear') with guards ``kind`` (report 4.7.2.3).

        Bends in torque mode; when both guards hold and the outer spring
        presses the wall (a clamp means pressing the wall), the
        inner bend gets 0 to release its torque so the other part can
        still move.
        """
        pair = self.guards.pair(kind, part)
        self._bends_in_torque(pair)
        try:
            self.wait_for(clamp_name(kind, part),
                          lambda v: clamp_state.clamped(self.guards, pair, v.angles, v.efforts),
                          '%s and %s on the wall' % (pair.describe(True), pair.outer.joint))
        except TimedOut as late:
            raise TimedOut('%s%s' % (late, self._where_the_clamp_stood(pair))) from late
        with self.writing():
            self.setpoint.set(pair.inner.joint, 0)

    def _where_the_clamp_stood(self, pair):
        """What a clamp that timed out stood on: its outer bend folded the
        other way, past straight by more than half its guard (twin: a 90 mm
        T-joint LEFT at 18 mm/s left Bend IV at +0.58 rad against its guard
        -0.60: turned the wrong way round, not short); or its outer spring
        pressing the wall short of its angle guard: the wall is nearer than
        this diameter's guards expect (twin: a 110 mm Clamp Straight in a
        90 mm pipe stood at -1.02 rad, its guard -1.25, for the whole 15 s);
        else ''."""
        view = self.feed.latest()
        outer = pair.outer
        if view is None:
            return ''
        angle = view.angles[outer.joint]
        if angle * outer.guard < 0 and abs(angle) > abs(outer.guard) / 2:
            return ('; %s stands at %+.2f rad, folded the other way from its guard %+.2f: the V turned the wrong '
                    'way round (it is not short of the wall)' % (outer.joint, angle, outer.guard))
        if angle <= outer.guard or not clamp_state.presses_wall(self.guards, outer, view.efforts):
            return ''
        return ('; %s presses the wall at %+.2f rad, short of its guard %+.2f: the wall is nearer than the %d mm '
                'guards expect (a narrower pipe than the goal says, or the part not lying where they assume)'
                % (outer.joint, angle, outer.guard, self.guards.pipe_diameter))

    def _bends_in_torque(self, pair):
        with self.writing():
            for bend in (pair.outer, pair.inner):
                self.control.set_mode(bend.joint, 'torque')
                self.setpoint.set(bend.joint, bend.setpoint)

    def unclamp(self, part, partial=False, row=None):
        """Open ``part``'s V fully (Home) or partially (re-adjust), 4.7.2.5.

        A partial unclamp leaves "a very open V" (4.7.2.5): at its guard the
        bends are held by their worms (PWM 0). With the unclamp torque left
        on they drove on past straight into a reverse V pressing the wall,
        and the rotation that follows then dragged the clamped part round
        (seen in the twin). The next clamp puts them back in torque.

        A full unclamp ends when the part is free as the clamp state reads
        it: angles open AND no spring pushing in the clamping direction.
        Falling open under its weight a bend can pass its angle guard with
        its spring still loaded the clamping way (twin: bend III -60 mNm),
        and held there it read as pressing after Home.

        ``row``: the guard row of a partial unclamp when not the plain one
        (Clamp Sideways' ``unclamp_partial_sideways``).
        """
        pair = self.guards.pair(row or ('unclamp_partial' if partial else 'unclamp'), part)
        self._bends_in_torque(pair)
        if partial:
            guard, text = (lambda v: pair.opened(v.angles)), pair.describe(False)
        else:
            moving = BendProgress(self.guards.unclamp, (pair.outer.joint, pair.inner.joint), 'unclamp %s' % part)
            guard = lambda v: (pair.opened(v.angles) and not clamp_state.pressing(self.guards, part, v.efforts)  # noqa: E731
                               or moving.check(v))
            text = '%s and no spring pressing' % pair.describe(False)
        self.wait_for('unclamp %s%s' % (part, ' partial' if partial else ''), guard, text)
        if partial:
            self.hold(pair.outer.joint, pair.inner.joint)

    def hold(self, *joints):
        """``joints`` held by their worm gears where they are (PWM 0).

        The zero setpoints go out before the mode, as in the safe hold
        (pirate.robot.hold): a mode change goes out at once, and PWM with
        the torque setpoint still on the wire drove the bend until the next
        setpoint array (Home's held inner spring then read as pressing now
        and then, test_pab_home_twin.py under load).
        """
        with self.writing():
            for joint in joints:
                self.setpoint.set(joint, 0)
            if self.setpoint.enabled:          # nothing goes out before Play
                self.setpoint.publish_now()
            for joint in joints:
                self.control.set_mode(joint, 'pwm')

    def rotate(self, target_rad, name='rotate'):
        """Rotational module to ``target_rad`` from aligned (4.7.2.2).

        Refused beyond +-0.7 rad (pirate.robot.safety); the part that is not
        clamped turns (Table 4.5).
        """
        if not safety.rotation_ok(target_rad):
            raise Refused('rotation %.3f rad beyond +-%.1f rad' % (target_rad, safety.ROTATION_MAX_RAD))
        tolerance = self.guards.rotate_tolerance
        with self.writing():
            self.control.set_mode('rotation', 'position')
            self.setpoint.set('rotation', units.rad_to_rotation(target_rad))
        self.wait_for(name, lambda v: abs(v.angles['rotation'] - target_rad) <= tolerance,
                   '|rotation - %.3f| <= %.4f' % (target_rad, tolerance))

    def align(self):
        """Rotation back to 0 (4.7.2.6): the front part follows the rear."""
        self.rotate(0.0, name='align')

    def move_front(self, kind='move_front'):
        """Front module up (or down) in PWM until its guard, then stop it."""
        move = self.guards.move(kind)
        with self.writing():
            self.control.set_mode('front_tilt', 'pwm')
            self.setpoint.set('front_tilt', move.setpoint)
        if move.setpoint >= 0:
            guard, text = (lambda v: v.angles['front_tilt'] >= move.guard), 'front_tilt >= %.3f' % move.guard
        else:
            guard, text = (lambda v: v.angles['front_tilt'] <= move.guard), 'front_tilt <= %.3f' % move.guard
        try:
            self.wait_for(report_kind(kind).replace('_', ' '), guard, text)
        finally:
            with self.control.wire_lock:    # 0 in PWM: what the hold writes too
                self.setpoint.set('front_tilt', 0)

    # --- safety -----------------------------------------------------------
    def safe_hold(self):
        """The safe hold of :mod:`pirate.robot.hold`, with the newest joint angles."""
        view = self.feed.latest()
        return safe_hold(self.setpoint, self.control, view.angles if view else None)
