"""Motion primitives (SPEC 7) over the real command arrays and a fake feed.

The fake feed records which guard each advanced primitive waits on and
checks it against hand-made states, so every test sees what went out before
the wait, the guard itself, and what went out after it.
"""
import math

import pytest

from pirate.robot import safety, tables, units
from pirate.state.feed import Cancelled, RobotView, SensorFrozen, TimedOut
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import turn_motions as motions
from pirate.sequencer.primitives import FrozenJoints, MotionPrimitives, Refused
from pirate.sequencer.server import PabContext

from fakes import command_arrays

JOINTS = ('front_tilt', 'bend_i', 'bend_ii', 'rotation', 'bend_iii', 'bend_iv')


#: Both outer springs at the clamp's torque (mNm): the V presses the wall.
ON_WALL = dict(bend_i=241.0, bend_iv=241.0)


def view(efforts=None, **angles):
    base = {name: 0.0 for name in JOINTS}
    base.update(angles)
    return RobotView(base, math.pi / 2, 0.0, 0.0, 1.0, ON_WALL if efforts is None else efforts)


class FakeFeed(object):
    """Stands in for RobotFeed: records waits, answers with scripted states.

    ``outcome`` None: the wait returns the first of ``states`` its guard
    accepts (AssertionError if none does, i.e. the guard is wrong); an
    exception instance: the wait raises it.
    """

    def __init__(self, states=(), outcome=None):
        self.states = list(states)
        self.outcome = outcome
        self.waits = []          # (describe, guard, timeout, setpoints at the time of the wait)
        self.current = view()
        self.arrays = None

    def latest(self):
        return self.current

    def check(self):
        """Neither cancelled nor without feedback (RobotFeed.check)."""

    def watch(self, check):
        """RobotFeed.watch: the frozen-sensor check (its own tests call it)."""

    def wait_until(self, guard, timeout, describe='guard'):
        self.waits.append((describe, guard, timeout, self.arrays()))
        if self.outcome is not None:
            raise self.outcome
        for state in self.states:
            if guard(state):
                return state
        raise AssertionError('no scripted state satisfies %s' % describe)


@pytest.fixture
def rig():
    wires, setpoint, control, limit = command_arrays()
    feed = FakeFeed()
    feed.arrays = setpoint.get_all
    prims = MotionPrimitives(setpoint, control, limit, feed)
    prims.use(GuardBook(*load_files()).for_diameter(90))
    return prims, feed, wires


# --- clamp / unclamp -------------------------------------------------------

@pytest.mark.parametrize('part, outer, inner', [('front', 'bend_i', 'bend_ii'),
                                                ('rear', 'bend_iv', 'bend_iii')])
def test_clamp_torque_guard_then_inner_released(rig, part, outer, inner):
    prims, feed, _ = rig
    feed.states = [view(**{outer: -0.76, inner: 0.40}),      # outer short of -0.77
                   view(**{outer: -0.80, inner: 0.34}),      # inner short of 0.35
                   view({inner: -194.0}, **{outer: -0.80, inner: 0.40}),  # angles, but short of the wall
                   view(**{outer: -0.77, inner: 0.35})]      # both exactly at the guard, on the wall
    prims.clamp(part)
    assert prims.control.mode_of(outer) == 'torque' and prims.control.mode_of(inner) == 'torque'
    describe, guard, timeout, during = feed.waits[0]
    idx = {name: i for i, name in enumerate(('camera_tilt', 'front_tilt', 'bend_i', 'bend_ii',
                                             'imu_module', 'rotation', 'bend_iii', 'bend_iv'))}
    assert during[idx[outer]] == 256 and during[idx[inner]] == -256   # written before the wait
    assert [guard(s) for s in feed.states] == [False, False, False, True]
    assert timeout == 15.0
    assert prims.setpoint.get(inner) == 0          # released after the guard (4.7.2.3)
    assert prims.setpoint.get(outer) == 256        # outer keeps pressing
    assert prims.executed == ['clamp %s' % part]


def test_custom_clamp_guards_and_names(rig):
    prims, feed, _ = rig
    feed.states = [view(bend_i=-0.70, bend_ii=0.30), view(bend_iv=-0.68, bend_iii=0.33),
                   view(bend_i=-0.72, bend_ii=0.30)]
    prims.clamp('front', 'clamp_front_custom_first')
    prims.clamp('rear', 'clamp_rear_custom')
    prims.clamp('front', 'clamp_front_custom')
    assert prims.executed == ['clamp front custom first', 'clamp rear custom', 'clamp front custom']
    # -0.70 satisfies the first-time custom guard (-0.69) but not the later one (-0.72)
    assert feed.waits[0][1](feed.states[0]) and not feed.waits[2][1](feed.states[0])


@pytest.mark.parametrize('partial, outer_guard, inner_guard', [(True, -0.48, 0.29), (False, -0.15, 0.07)])
def test_unclamp_rear(rig, partial, outer_guard, inner_guard):
    prims, feed, _ = rig
    prims.setpoint.set('bend_iv', 256)
    feed.states = [view({}, bend_iv=outer_guard - 0.01, bend_iii=inner_guard),
                   view({}, bend_iv=outer_guard, bend_iii=inner_guard + 0.01),
                   view(ON_WALL, bend_iv=outer_guard, bend_iii=inner_guard),   # open, a spring still pressing
                   view({}, bend_iv=outer_guard, bend_iii=inner_guard)]
    prims.unclamp('rear', partial=partial)
    _, guard, _, during = feed.waits[0]
    assert during[7] == -100 and during[6] == 150      # bend_iv, bend_iii
    # A full unclamp ends when the part is free (angles AND springs); a partial one at its angles.
    assert [guard(s) for s in feed.states] == [False, False, partial, True]
    assert prims.executed == ['unclamp rear%s' % (' partial' if partial else '')]


def test_partial_unclamp_holds_the_open_v_zero_setpoints_on_the_wire_before_pwm(rig):
    """Report 4.7.2.5: a very open V, held by the worms (PWM 0); the zeros
    go out before the mode change, which goes out at once (as the safe hold)."""
    prims, feed, wires = rig
    prims.setpoint.enabled = True                 # after Play
    order = []
    for name in ('setpoint', 'control'):
        publish = wires[name].publish
        wires[name].publish = lambda data, name=name, publish=publish: (order.append((name, list(data))),
                                                                        publish(data))
    feed.states = [view({}, bend_iv=-0.47, bend_iii=0.28)]
    prims.unclamp('rear', partial=True)
    iv, iii = tables.element('bend_iv').index, tables.element('bend_iii').index
    assert prims.control.mode_of('bend_iv') == prims.control.mode_of('bend_iii') == 'pwm'
    modes = [(i, data[iii]) for i, (wire, data) in enumerate(order) if wire == 'control']
    torque = next(i for i, mode in modes if mode == safety.MODE_CODES['torque'])
    held = next(i for i, mode in modes if i > torque and mode == safety.MODE_CODES['pwm'])
    on_the_wire = [data for wire, data in order[torque:held] if wire == 'setpoint'][-1]
    assert on_the_wire[iv] == on_the_wire[iii] == 0


def test_full_unclamp_front_uses_its_own_guards(rig):
    prims, feed, _ = rig
    feed.states = [view({}, bend_i=-0.21, bend_ii=0.0), view({}, bend_i=-0.2, bend_ii=0.03)]
    prims.unclamp('front')
    assert [feed.waits[0][1](s) for s in feed.states] == [False, True]


@pytest.mark.parametrize('bend_iv, said', [
    (+0.58, 'bend_iv stands at +0.58 rad, folded the other way from its guard -0.77: the V turned the wrong way'),
    (-0.50, 'bend_iv presses the wall at -0.50 rad, short of its guard -0.77: the wall is nearer'),
    (+0.20, 'bend_iv presses the wall at +0.20 rad, short of its guard -0.77'),    # under half: not "folded"
])
def test_a_clamp_that_timed_out_says_where_its_outer_bend_stood(rig, bend_iv, said):
    """The abort says what happened: a V folded the wrong way round is not
    short of the wall (twin: a T-joint LEFT at 18 mm/s, Bend IV at +0.58)."""
    prims, feed, _ = rig
    feed.outcome = TimedOut('clamp rear: not reached within 15.0 s')
    feed.current = view(bend_iv=bend_iv, bend_iii=0.1)
    with pytest.raises(TimedOut) as late:
        prims.clamp('rear')
    assert said in str(late.value)


def test_a_corner_clamp_that_timed_out_says_what_it_read(rig):
    """Clamping the front at the corner: the abort names where Bend II, Bend
    I's spring and the middle (Bend III) stood, what a re-sent turn decides from."""
    prims, feed, _ = rig
    feed.outcome = TimedOut('clamp front at the corner: not reached within 15.0 s')
    feed.current = view({'bend_i': -120.0}, bend_ii=1.48, bend_iii=0.81)
    ctx = PabContext(prims, feed, prims.guards, None, lambda *state: None)
    with pytest.raises(TimedOut) as late:
        motions.clamp_at_corner(ctx)
    assert str(late.value).endswith("bend_ii stood at +1.48 rad, bend_i's spring at -120 mNm, bend_iii at +0.81 rad")


def stamped(stamp, efforts=None, **angles):
    return view(efforts, **angles)._replace(stamp=stamp)


def test_a_full_unclamp_whose_bends_stand_still_is_blocked(rig):
    """Half round a junction the walls hold the bends (twin: a turn cancelled
    while steering, then Home): once neither bend nor spring has moved for
    config/sequencer.yaml unclamp.no_progress_s of robot time, the unclamp
    ends blocked instead of pushing at the unclamp torque for 15 s."""
    prims, feed, _ = rig
    window = prims.guards.unclamp['no_progress_s']
    feed.states = [stamped(t, {'bend_i': 120.0, 'bend_ii': -80.0}, bend_i=-0.45, bend_ii=-0.38)
                   for t in (0.0, window / 2, window, window + 0.1)]
    with pytest.raises(TimedOut, match='unclamp front blocked: bend_i -0.45 rad, bend_ii -0.38 rad stood still'):
        prims.unclamp('front')


@pytest.mark.parametrize('moving', ['bend', 'spring'])
def test_a_slow_full_unclamp_is_not_blocked(rig, moving):
    """A bend creeping open, or its motor still unwinding the spring with the
    angle standing, is progress: the unclamp runs on to its guard."""
    prims, feed, _ = rig
    window = prims.guards.unclamp['no_progress_s']
    states = []
    for step in range(int(4 * window) + 1):         # one state a second of robot time
        angle = -0.9 + (0.02 * step if moving == 'bend' else 0.0)
        spring = 200.0 - (0.0 if moving == 'bend' else 15.0 * step)
        states.append(stamped(float(step), {'bend_i': spring}, bend_i=angle, bend_ii=0.45))
    feed.states = states + [stamped(len(states) + 1.0, {}, bend_i=-0.2, bend_ii=0.03)]
    prims.unclamp('front')
    assert prims.executed == ['unclamp front']


# --- rotate / align --------------------------------------------------------

@pytest.mark.parametrize('target', [0.71, -0.71, 0.7 + 1e-6 + 0.001, math.nan, math.inf])
def test_rotation_beyond_limit_refused_and_nothing_sent(rig, target):
    prims, feed, wires = rig
    before = prims.setpoint.get_all()
    with pytest.raises(Refused):
        prims.rotate(target)
    assert prims.setpoint.get_all() == before and feed.waits == [] and wires['control'].sent == []


@pytest.mark.parametrize('target', [0.7, -0.7, 0.25, 0.0])
def test_rotate_position_mode_and_tolerance(rig, target):
    prims, feed, _ = rig
    feed.states = [view(rotation=target + 0.05), view(rotation=target - 0.042)]
    prims.rotate(target, name='rotate rear')
    assert prims.control.mode_of('rotation') == 'position'
    assert prims.setpoint.get('rotation') == units.rad_to_rotation(target)
    guard = feed.waits[0][1]
    assert not guard(feed.states[0]) and guard(feed.states[1])
    assert prims.executed == ['rotate rear']


def test_align_is_rotate_to_zero(rig):
    prims, feed, _ = rig
    prims.setpoint.set('rotation', 500)
    feed.states = [view(rotation=0.01)]
    prims.align()
    assert prims.setpoint.get('rotation') == 0 and prims.executed == ['align']


# --- move front ------------------------------------------------------------

@pytest.mark.parametrize('kind, guard_rad', [('move_front', 0.4), ('move_front_first', 0.105),
                                             ('move_front_later', 0.3)])
def test_move_front_pwm_until_guard_then_stop(rig, kind, guard_rad):
    prims, feed, _ = rig
    feed.states = [view(front_tilt=guard_rad - 0.001), view(front_tilt=guard_rad)]
    prims.move_front(kind)
    _, guard, _, during = feed.waits[0]
    assert during[1] == 32 and prims.control.mode_of('front_tilt') == 'pwm'
    assert [guard(s) for s in feed.states] == [False, True]
    assert prims.setpoint.get('front_tilt') == 0


def test_move_front_down_guard_is_below(rig):
    prims, feed, _ = rig
    feed.states = [view(front_tilt=0.4), view(front_tilt=0.05)]
    prims.move_front('move_front_down')
    _, guard, _, during = feed.waits[0]
    assert during[1] == -32 and [guard(s) for s in feed.states] == [False, True]
    assert prims.setpoint.get('front_tilt') == 0


@pytest.mark.parametrize('failure', [Cancelled('cancelled'), TimedOut('late')])
def test_move_front_stops_the_front_when_interrupted(rig, failure):
    prims, feed, _ = rig
    feed.outcome = failure
    with pytest.raises(type(failure)):
        prims.move_front('move_front')
    assert feed.waits[0][3][1] == 32               # it was moving
    assert prims.setpoint.get('front_tilt') == 0    # and is stopped


def test_interrupted_wait_propagates_from_clamp(rig):
    prims, feed, _ = rig
    feed.outcome = Cancelled('cancelled')
    with pytest.raises(Cancelled):
        prims.clamp('rear')


# --- drive -----------------------------------------------------------------

@pytest.mark.parametrize('mm_s', [170.0, -170.0, 150.0, 0.0])
def test_drive_within_limit(rig, mm_s):
    prims, _, _ = rig
    prims.drive_at_velocity(mm_s)
    assert prims.control.mode_of('wheels') == 'velocity'
    assert prims.setpoint.get('wheels') == units.mm_s_to_wheel_counts(mm_s)


@pytest.mark.parametrize('mm_s', [170.5, 200.0, -200.0, math.nan, math.inf])
def test_drive_above_limit_refused(rig, mm_s):
    prims, _, wires = rig
    with pytest.raises(Refused) as info:
        prims.drive_at_velocity(mm_s)
    assert '170' in str(info.value)
    assert prims.setpoint.get('wheels') == 0 and wires['control'].sent == []


# --- safe hold (pirate.robot.hold: bends/front PWM 0, wheels 0, rotation held) ---

def test_safe_hold_stops_everything_and_holds_rotation(rig):
    prims, feed, wires = rig
    for bend in ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv'):
        prims.control.set_mode(bend, 'torque')
        prims.setpoint.set(bend, 256)
    prims.drive_at_velocity(150)
    prims.control.set_mode('front_tilt', 'pwm')
    prims.setpoint.set('front_tilt', 32)
    prims.control.set_mode('rotation', 'position')
    prims.setpoint.set('rotation', units.rad_to_rotation(0.6))
    feed.current = view(rotation=0.3)
    before = len(wires['setpoint'].sent)
    prims.safe_hold()
    assert len(wires['setpoint'].sent) == before + 1          # published at once, no tick
    sent = wires['setpoint'].sent[-1]
    for name in ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv', 'front_tilt', 'wheels'):
        assert prims.setpoint.get(name) == 0, name
    assert sent[1] == sent[2] == sent[3] == sent[6] == sent[7] == sent[11] == 0
    assert sent[5] == units.rad_to_rotation(0.3)             # held where it is
    assert prims.control.mode_of('rotation') == 'position'
    for name in ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv', 'front_tilt'):
        assert prims.control.mode_of(name) == 'pwm', name    # worm gear holds, spring stays loaded


def test_safe_hold_zeroes_before_the_mode_changes(rig):
    """No motor may see a torque setpoint as a PWM duty: 0 goes out first."""
    prims, _, wires = rig
    order = []
    for name in ('setpoint', 'control'):
        wire = wires[name]
        wire.publish = (lambda data, name=name, wire=wire: (order.append((name, list(data))),
                                                              wire.sent.append(list(data))))
    prims.control.set_mode('bend_i', 'torque')
    prims.setpoint.set('bend_i', 256)
    del order[:]
    prims.safe_hold()
    first_control = [i for i, (name, _) in enumerate(order) if name == 'control'][0]
    zeroed = [i for i, (name, data) in enumerate(order) if name == 'setpoint' and data[2] == 0]
    assert zeroed and zeroed[0] < first_control


@pytest.mark.parametrize('reading', [-0.9, 15.36, float('nan')])
def test_safe_hold_keeps_the_rotation_target_on_an_implausible_reading(rig, reading):
    """A reading beyond +-0.7 rad is a bad sensor, not a place to go.

    (It used to be saturated: a bogus 15.36 rad drove the rotation to +0.7.)
    """
    prims, feed, _ = rig
    prims.control.set_mode('rotation', 'position')
    prims.setpoint.set('rotation', units.rad_to_rotation(0.2))
    feed.current = view(rotation=reading)
    prims.safe_hold()
    assert prims.setpoint.get('rotation') == units.rad_to_rotation(0.2)
    assert abs(units.rotation_to_rad(prims.setpoint.get('rotation'))) <= safety.ROTATION_MAX_RAD


def test_safe_hold_front_in_position_mode_stops_in_pwm(rig):
    prims, feed, _ = rig
    prims.control.set_mode('front_tilt', 'position')
    prims.setpoint.set('front_tilt', 600)
    feed.current = view(front_tilt=0.2)
    prims.safe_hold()
    assert prims.setpoint.get('front_tilt') == 0 and prims.control.mode_of('front_tilt') == 'pwm'


def test_safe_hold_without_any_state_still_stops(rig):
    prims, feed, wires = rig
    feed.current = None
    prims.drive_at_velocity(50)
    prims.setpoint.set('bend_iii', -200)
    prims.safe_hold()
    assert wires['setpoint'].sent[-1][11] == 0 and wires['setpoint'].sent[-1][6] == 0


def test_follow_ends_with_its_own_timeout_when_a_state_lands_on_the_deadline(rig):
    """A state stamped exactly at the end of ``follow``'s time ends it with
    TimedOut naming the primitive and its time, rather than a zero-length
    wait for one more state (which the real feed reported as a wall-clock
    timeout of 0.0 s: a swing round a corner that stalled)."""
    prims, feed, _ = rig
    feed.states = [view()._replace(stamp=stamp) for stamp in (1.5, 2.0)]
    acted = []
    with pytest.raises(TimedOut, match=r'swing: bend_iii >= 1.65 not reached within 1.0 s'):
        prims.follow('swing', acted.append, lambda v: False, 'bend_iii >= 1.65', 1.0)
    assert [v.stamp for v in acted] == [1.0, 1.5] and [w[2] for w in feed.waits] == [1.0, 0.5]


# --- a frozen sensor ---------------------------------------------------------------

def _bend_i(stamp, angle, effort):
    return RobotView({'bend_i': angle}, math.pi / 2, 0.0, 0.0, stamp, {'bend_i': effort})


def test_a_driven_bend_whose_readings_stand_still_is_frozen():
    """Board 22 answering a stuck Bend I during a turn was never noticed."""
    frozen = FrozenJoints(lambda joint, view: 30.0, joints=('bend_i',))
    for cycle in range(7):                  # 0.6 s driven, not moving: not yet
        frozen.check(_bend_i(10.0 + 0.1 * cycle, -0.5, -80.0))
    with pytest.raises(SensorFrozen, match='bend_i reads frozen'):
        frozen.check(_bend_i(10.7, -0.5, -80.0))


@pytest.mark.parametrize('moves', [(0.004, 0.0), (0.0, 3.0)])
def test_a_driven_bend_moving_its_angle_or_its_spring_is_not_frozen(moves):
    frozen = FrozenJoints(lambda joint, view: 30.0, joints=('bend_i',))
    for cycle in range(30):
        step = cycle // 4                   # a slow bend: a few counts every 0.4 s
        frozen.check(_bend_i(10.0 + 0.1 * cycle, -0.5 + moves[0] * step, -80.0 + moves[1] * step))


def test_a_bend_not_driven_may_stand_still():
    """A clamped bend at its torque setpoint (no demand) or held in PWM stands still."""
    driven = {'now': False}
    frozen = FrozenJoints(lambda joint, view: 30.0 if driven['now'] else 0.0, joints=('bend_i',))
    for cycle in range(30):
        frozen.check(_bend_i(10.0 + 0.1 * cycle, -0.5, -80.0))
    driven['now'] = True                    # a new setpoint: the window starts now
    for cycle in range(30, 37):
        frozen.check(_bend_i(10.0 + 0.1 * cycle, -0.5, -80.0))


def test_the_torque_demand_is_setpoint_within_its_limit_minus_the_spring(rig):
    prims, _, _ = rig
    prims.control.set_mode('bend_i', 'torque')
    prims.setpoint.set('bend_i', -60)
    at = lambda effort: _bend_i(1.0, 0.0, effort)     # noqa: E731
    assert prims.torque_demand('bend_i', at(-30.0)) == pytest.approx(-units.spring_to_mnm(-60) - 30.0, abs=1.0)
    assert prims.torque_demand('bend_i', at(-62.0)) == 0.0            # at its setpoint: at rest
    assert prims.torque_demand('bend_i', at(-93.0)) == 0.0            # at the report's 400 mNm per 256: at rest
    prims.limit.set('bend_i', 20)
    assert prims.torque_demand('bend_i', at(-20.0)) == 0.0            # at its limit
    prims.control.set_mode('bend_i', 'pwm')
    assert prims.torque_demand('bend_i', at(-88.0)) == 0.0


def test_a_bend_pressing_a_wall_short_of_its_setpoint_is_not_driven(rig):
    """Its motor at its stall short of the clamp setpoint stands still by
    physics: pressing the way it is driven with a clamp's effort it is not
    counted as driven; the same spring against an opening setpoint is."""
    prims, _, _ = rig
    prims.control.set_mode('bend_i', 'torque')
    prims.setpoint.set('bend_i', 256)
    at = lambda effort: _bend_i(1.0, -0.8, effort)     # noqa: E731
    assert prims.torque_demand('bend_i', at(220.0)) == 0.0           # presses the wall at 220 of 256
    assert prims.torque_demand('bend_i', at(150.0)) > 0.0            # short of a clamp's effort: driven
    prims.setpoint.set('bend_i', -100)                               # opening, the spring still clamped
    assert prims.torque_demand('bend_i', at(220.0)) > 0.0


def test_a_bend_whose_board_does_not_answer_is_not_called_frozen():
    """Its values are held because its board is silent: the state says so
    (board N silent), not the frozen check (the silent-board rostest at x2)."""
    frozen = FrozenJoints(lambda joint, view: 30.0, joints=('bend_i',))
    for cycle in range(12):
        frozen.check(_bend_i(10.0 + 0.1 * cycle, -0.5, -80.0)._replace(missed_boards=(22,) if cycle else ()))
