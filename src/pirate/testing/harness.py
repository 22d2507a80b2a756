"""The whole sequencer against the simulated robot (the physics twin), in one process, no ROS.

Same objects as the ROS stack (Setpoint/Control/Limit, StateAssembler,
RobotFeed, MotionPrimitives, PirateServer), the topics replaced by direct
calls. A robot thread steps the model one Mega cycle (0.1 s of robot time,
5 PICO steps) at a time and pushes its state, in lockstep with the
sequencer (:mod:`pirate.testing.lockstep`): a cycle starts only when every
consumer of the robot's state waits for the next one, so a run is the same
on a busy host as on an idle one, and runs as fast as the CPU allows. Every
clock above the robot reads robot time (``SimHarness.clock``): the
feedback watchdog, the primitives' timeouts, the Mega's watchdog, the
state node's silent boards. Used by the fast test tier and the benchmarks;
the rostests cover the ROS wiring.

Robot time passes only while someone waits for it: a goal run by
:meth:`SimHarness.execute` (it takes part for its whole run), or
:meth:`SimHarness.wait_robot` / :meth:`SimHarness.run_for`. An action at a
robot instant (a cancel, a fault) goes in :meth:`SimHarness.when`: it runs
between two cycles, while every consumer waits.
"""
import threading
import time

from pirate.robot import commands, tables
from pirate.state.feed import RobotFeed, RobotView
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.primitives import MotionPrimitives
from pirate.sequencer.server import PirateServer
from pirate.sim import twin_robot
from pirate.sim.robot_end import make_robot
from pirate.sim.watchdog import MegaWatchdog
from pirate.state.assembler import BadState, StateAssembler, pab_blocker
from pirate.testing.lockstep import Lockstep

PICO_PERIOD_S = 0.02
STEPS_PER_CYCLE = 5
START_S = 1.0                   # robot time of the first cycle's start


class _Wire(object):
    """A publisher that records what went out (robot time, data) and hands it to the robot."""

    def __init__(self, clock, on_publish):
        self.sent = []
        self._clock = clock
        self._on_publish = on_publish

    def publish(self, data):
        self.sent.append((self._clock(), list(data)))
        self._on_publish()


def view_of(snapshot, stamp):
    """A :class:`RobotView` from a :class:`pirate.state.assembler.Snapshot`."""
    return RobotView(dict(zip(snapshot.name, snapshot.position)), snapshot.orientation,
                     snapshot.odometry, snapshot.velocity, stamp, dict(zip(snapshot.name, snapshot.effort)),
                     dict(snapshot.part_odometry), snapshot.missed)


class SimHarness(object):
    """Robot + sequencer, wired directly. Use as a context manager.
    The robot is the physics twin: ``model_args`` go to
    :func:`pirate.sim.robot_end.make_robot` (``world=``, default the straight
    pipe of ``pipe_diameter``); a unit test that needs the fast fake passes
    ``robot=FakeRobot(...)`` (:mod:`pirate.sim.fake_robot`) instead.
    ``pace``: at most this many robot s per wall s, for a test of races on
    the wall clock that needs the robot slower than the CPU runs it (None:
    as fast as the CPU allows)."""

    def __init__(self, feedback_timeout=None, robot=None, pace=None, **model_args):
        self.model = robot if robot is not None else make_robot(**model_args)
        self.pace = pace
        self._lock = threading.RLock()
        self.watchdog = MegaWatchdog()
        self.clock = Lockstep(START_S, PICO_PERIOD_S * STEPS_PER_CYCLE, self._turn)
        self.wires = {name: _Wire(self.clock, lambda name=name: self._apply(name))
                      for name in ('setpoint', 'control', 'limit')}
        self.control = commands.Control(self.wires['control'], list)
        self.setpoint = commands.Setpoint(self.wires['setpoint'], list, self.control)
        self.limit = commands.Limit(self.wires['limit'], list)
        book = GuardBook(*load_files())
        self.feed = RobotFeed(feedback_timeout or book.common['feedback_timeout'], clock=self.clock,
                              wall_factor=book.common['wall_timeout_factor'], wait=self.clock.wait)
        self.setpoint.measured = lambda: self.feed.latest().angles if self.feed.fresh() else None
        self.prims = MotionPrimitives(self.setpoint, self.control, self.limit, self.feed)
        self.feedback = []
        self.log = []
        self.server = PirateServer(self.prims, self.feed, book, self.start_robot,
                                   feedback=self.feedback.append, log=self.log.append)
        self.assembler = StateAssembler()
        self.frozen = False           # True: the robot stops reporting
        self.silent = set()           # boards that stop answering (the Mega says so in their place)
        self.failure = None           # what stopped the robot thread, if it failed
        self._due = []                # (condition, action) of :meth:`when`
        self._due_lock = threading.Lock()
        self._ticks = threading.Condition()
        self._thread = threading.Thread(target=self.clock.robot_loop, daemon=True)

    @property
    def robot_time(self):
        """Robot seconds now (the end of the last cycle)."""
        return self.clock()

    def start_robot(self):
        """What the manager does when a goal starts: PLAY and paced arrays."""
        commands.play(self.control, self.setpoint, self.limit)
        self.setpoint.tick()

    def _apply(self, which=None):
        """The Mega: take the arrays (STOP to every board while its watchdog is tripped)."""
        with self._lock:
            if which == 'setpoint':
                self.watchdog.setpoint_arrived(self.clock())
            self.model.command(self.setpoint.get_all(), self.watchdog.boards_see(self.control.get_all()),
                               self.limit.get_all())

    def _turn(self):
        """The robot's turn, every consumer waiting: the actions of :meth:`when`
        that fell due, else one cycle."""
        try:
            if self._run_due():
                self.clock.nudge()
            else:
                self._cycle()
        except Exception as failure:  # pylint: disable=broad-except; the goal must end, not hang
            self.failure = failure
            self.feed.lose('the simulated robot failed: %r' % failure)
            self.clock.close()

    def _cycle(self):
        """One Mega cycle, while every consumer waits: the model steps 0.1 s,
        the manager's 10 Hz timer sends what the sequencer wrote for the last
        state (it acts from the next cycle: on the robot the timer runs
        apart from the states, up to a cycle after), the new state is
        reported."""
        if self.watchdog.poll(self.clock()):
            self._apply()
        with self._lock:
            for _ in range(STEPS_PER_CYCLE):
                self.model.step(PICO_PERIOD_S)
            states = [(b, self.model.small_state(b)) for b in tables.BOARDS]
        if self.pace:
            time.sleep(PICO_PERIOD_S * STEPS_PER_CYCLE / self.pace)
        self.setpoint.tick()
        self.limit.tick()
        self.clock.advance()
        if not self.frozen:
            self._report([(b | tables.NO_ANSWER, [0] * tables.SMALL_STATE_SIZE) if b in self.silent else (b, d)
                          for b, d in states])
        self.clock.wake()

    def _run_due(self):
        """Run the actions of :meth:`when` whose condition holds; True when one ran."""
        with self._due_lock:
            due = [entry for entry in self._due if entry[0]()]
            self._due = [entry for entry in self._due if entry not in due]
        for _, action in due:
            action()
        return bool(due)

    def when(self, condition, action):
        """Call ``action()`` before the first cycle at which ``condition()``
        holds, checked between cycles while every consumer waits: a cancel or
        a fault at a robot instant, the same in every run. Returns a function
        that drops the action if it has not run yet."""
        entry = (condition, action)
        with self._due_lock:
            self._due.append(entry)

        def forget():
            with self._due_lock:
                self._due = [other for other in self._due if other is not entry]
        return forget

    def wait_robot(self, condition, robot_s):
        """Wait as a consumer until ``condition()`` holds or ``robot_s`` of
        robot time passed; return ``condition()``."""
        end = self.clock() + robot_s - 1e-9
        with self._ticks:
            while not condition() and self.clock() < end and not self.clock.closed:
                self.clock.wait(self._ticks, 0.1)
        return condition()

    def run_for(self, robot_s):
        """Wait as a consumer while ``robot_s`` of robot time pass."""
        self.wait_robot(lambda: False, robot_s)

    def _report(self, states):
        """What the state node and the manager do with one Mega cycle.

        The assembler's clock is robot time here (the state node uses the
        wall clock, which is robot time on the robot).
        """
        now = self.robot_time
        for board, data in states:
            try:
                self.assembler.update(board, data, now)
            except BadState as bad:     # dropped whole, as the state node does
                self.log.append(str(bad))
        snap = self.assembler.snapshot(now)
        blocker = pab_blocker(snap.stale, snap.silent, snap.age)
        if blocker:
            self.feed.lose(blocker)
        else:
            self.feed.push(view_of(snap, self.robot_time))

    def __enter__(self):
        self._thread.start()
        self.wait_robot(lambda: self.feed.latest() is not None, 5.0)
        return self

    def __exit__(self, *exc):
        self.clock.close()
        self._thread.join(10.0)
        self.feed.lose('the simulated robot stopped')
        if self.failure is not None and exc[0] is None:
            raise self.failure

    def ground_truth(self):
        """The twin's ground truth (tests and benchmarks only), consistent
        with one robot step."""
        with self._lock:
            return self.model.ground_truth()

    def travel_mm(self):
        """True position of the rotational module along a straight pipe
        (the world's x), mm: ground truth, tests and benchmarks only."""
        return self.ground_truth()['poses'][twin_robot.ROTATIONAL_FRONT][0][0] * 1000.0

    def wheel_mm_s(self):
        """The fastest wheel's true surface speed, mm/s: ground truth, tests
        and benchmarks only."""
        with self._lock:
            radius_mm = self.model.config['geometry']['wheel_diameter_m'] * 500.0
            return max(abs(self.model.rate(twin_robot.wheel_joint(b))) for b in tables.DRIVE_BOARDS) * radius_mm

    def goal(self, name, pipe_diameter=90, distance=0.0, speed=0.0, option=0):
        """A goal object with the fields of Pirate.action's goal."""
        return _Goal(name, pipe_diameter, distance, speed, option)

    def execute(self, goal):
        """Reserve and run ``goal``: (reason refused, None) or (None, Outcome).
        The calling thread takes part in the lockstep for the whole run."""
        with self.clock.taking_part():
            reason = self.server.reserve(goal)
            if reason:
                return reason, None
            return None, self.server.run(goal)

    def execute_reserved(self, goal):
        """Run ``goal``, reserved already (``server.reserve``), to its Outcome,
        taking part in the lockstep for the whole run."""
        with self.clock.taking_part():
            return self.server.run(goal)


class _Goal(object):
    __slots__ = ('name', 'pipe_diameter', 'distance', 'speed', 'option')

    def __init__(self, name, pipe_diameter, distance, speed, option):
        self.name, self.pipe_diameter, self.distance = name, pipe_diameter, distance
        self.speed, self.option = speed, option
