"""The whole sequencer against the simulated robot (the physics twin), in one process, no ROS.

Same objects as the ROS stack (Setpoint/Control/Limit, StateAssembler,
RobotFeed, MotionPrimitives, PirateServer), the topics replaced by direct
calls. A robot thread steps the model and pushes a state every Mega cycle
(0.1 s of robot time), pacing itself at ``speedup`` times real time, so the
wall-clock feedback watchdog behaves as with a real robot. Used by the fast
test tier and the benchmarks; the rostests cover the ROS wiring.

The feedback watchdog and the Mega's watchdog measure silence on
``SimHarness.clock``, a :class:`pirate.state.robot_clock.RobotClock` ticked
by every robot cycle: on a loaded machine a simulated robot that falls behind its
pacing is late, not silent (CI saw "no robot state for 0.32 s" from a robot
thread that was merely descheduled); a robot that steps on time but reports
nothing (``frozen``, a silent board) is still noticed after the same wall
time as a real one.
"""
import threading
import time

from pirate.robot import commands, tables
from pirate.state.feed import RobotFeed, RobotView
from pirate.state.robot_clock import RobotClock
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.primitives import MotionPrimitives
from pirate.sequencer.server import PirateServer
from pirate.sim import twin_robot
from pirate.sim.robot_end import make_robot
from pirate.sim.watchdog import MegaWatchdog
from pirate.state.assembler import BadState, StateAssembler, pab_blocker

PICO_PERIOD_S = 0.02
STEPS_PER_CYCLE = 5


class _Wire(object):
    """A publisher that records what went out and hands it to the robot."""

    def __init__(self, on_publish):
        self.sent = []
        self._on_publish = on_publish

    def publish(self, data):
        self.sent.append((time.monotonic(), list(data)))
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
    ``robot=FakeRobot(...)`` (:mod:`pirate.sim.fake_robot`) instead."""

    def __init__(self, speedup=20.0, feedback_timeout=None, robot=None, **model_args):
        self.model = robot if robot is not None else make_robot(**model_args)
        self.speedup = speedup
        self._lock = threading.RLock()
        self.watchdog = MegaWatchdog()
        self.robot_time = 1.0
        self.clock = RobotClock()
        self.wires = {name: _Wire(lambda name=name: self._apply(name))
                      for name in ('setpoint', 'control', 'limit')}
        self.control = commands.Control(self.wires['control'], list)
        self.setpoint = commands.Setpoint(self.wires['setpoint'], list, self.control)
        self.limit = commands.Limit(self.wires['limit'], list)
        book = GuardBook(*load_files())
        self.feed = RobotFeed(feedback_timeout or book.common['feedback_timeout'],
                              wall_factor=book.common['wall_timeout_factor'], robot_clock=self.clock)
        self.setpoint.measured = lambda: self.feed.latest().angles if self.feed.fresh() else None
        self.prims = MotionPrimitives(self.setpoint, self.control, self.limit, self.feed)
        self.feedback = []
        self.log = []
        self.server = PirateServer(self.prims, self.feed, book, self.start_robot,
                                   feedback=self.feedback.append, log=self.log.append)
        self.assembler = StateAssembler()
        self.frozen = False           # True: the robot stops reporting
        self.silent = set()           # boards that stop answering (the Mega skips them)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._robot_loop, daemon=True)

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

    def _robot_loop(self):
        wall_next = time.monotonic()
        while not self._stop.is_set():
            if self.watchdog.poll(self.clock()):
                self._apply()
            with self._lock:
                for _ in range(STEPS_PER_CYCLE):
                    self.model.step(PICO_PERIOD_S)
                self.robot_time += PICO_PERIOD_S * STEPS_PER_CYCLE
                states = [(b, self.model.small_state(b)) for b in tables.BOARDS]
            self.clock.tick()
            if not self.frozen:
                self._report([(b, d) for b, d in states if b not in self.silent])
            self.setpoint.tick()       # the manager's 10 Hz timer, robot time
            self.limit.tick()
            wall_next += PICO_PERIOD_S * STEPS_PER_CYCLE / self.speedup
            time.sleep(max(0.0, wall_next - time.monotonic()))

    def _report(self, states):
        """What the state node and the manager do with one Mega cycle.

        The assembler's clock is robot time here, so a silent board is
        noticed after the same robot time at any speedup (the state node
        uses the wall clock, which is robot time on the robot).
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
        deadline = time.monotonic() + 5.0
        while self.feed.latest() is None and time.monotonic() < deadline:
            time.sleep(0.001)
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join(2.0)

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
        """Reserve and run ``goal``: (reason refused, None) or (None, Outcome)."""
        reason = self.server.reserve(goal)
        if reason:
            return reason, None
        return None, self.server.run(goal)


class _Goal(object):
    __slots__ = ('name', 'pipe_diameter', 'distance', 'speed', 'option')

    def __init__(self, name, pipe_diameter, distance, speed, option):
        self.name, self.pipe_diameter, self.distance = name, pipe_diameter, distance
        self.speed, self.option = speed, option
