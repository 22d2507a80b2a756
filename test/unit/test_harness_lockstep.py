"""The in-process twin runs in lockstep with the sequencer: a run is a
function of its inputs alone.

The robot steps a cycle only when every consumer of its state waits for the
next one, so the same case gives the same record to the last digit, run
alone or beside a process and a thread burning the CPU (the same interpreter:
the GIL contended too). Before, the robot thread paced itself on the wall
clock beside the sequencer's thread: one case's records differed by up to
2.7 robot s, 0.0055 rad of end roll and 3 primitives between two runs.
"""
import subprocess
import sys
import threading

from pirate.sim.fake_robot import FakeRobot
from pirate.testing.harness import SimHarness
from pirate.testing.lockstep import Lockstep

CLAMP_STRAIGHT = 0
NOMINAL_ROLL = 1.45         # Table 6.2: the re-adjust pass, the branchiest Clamp Straight


def clamp_straight_record():
    """One Clamp Straight case on the twin: every figure a sweep records, unrounded."""
    with SimHarness(world='straight_90', orientation=NOMINAL_ROLL, seed=3) as h:
        h.run_for(1.0)
        started = h.robot_time
        reason, outcome = h.execute(h.goal(CLAMP_STRAIGHT))
        ended = h.robot_time
        h.run_for(2.0)
        truth = h.ground_truth()
        return {'refused': reason, 'status': outcome.status, 'message': outcome.message,
                'robot_s': repr(ended - started), 'primitives': list(h.prims.executed),
                'roll': repr(truth['roll']), 'front_roll': repr(truth['front_roll']),
                'contacts': sorted(truth['wheel_contacts']), 'joints': repr(h.feed.latest().angles),
                'setpoints': [data for _, data in h.wires['setpoint'].sent]}


def burning():
    """A thread and a process busy on the CPU until the returned stop() is called."""
    process = subprocess.Popen([sys.executable, '-c', 'while True: pass'])
    done = threading.Event()

    def spin():
        while not done.is_set():
            sum(range(1000))
    thread = threading.Thread(target=spin, daemon=True)
    thread.start()

    def stop():
        done.set()
        thread.join(5.0)
        process.kill()
        process.wait(5.0)
    return stop


def test_a_clamp_straight_gives_the_same_record_every_run_on_a_busy_host_too():
    first = clamp_straight_record()
    assert first['status'] == 'succeeded', first['message']
    assert clamp_straight_record() == first
    stop = burning()
    try:
        loaded = clamp_straight_record()
    finally:
        stop()
    assert loaded == first


def test_a_cancel_at_a_robot_instant_lands_on_the_same_cycle_every_run():
    """A cancel put in ``when`` runs between two cycles, every consumer waiting."""
    def cancelled():
        with SimHarness(robot=FakeRobot(orientation=NOMINAL_ROLL)) as h:
            at = h.robot_time + 3.05
            h.when(lambda: h.robot_time >= at, h.server.cancel)
            _, outcome = h.execute(h.goal(CLAMP_STRAIGHT))
            return outcome.status, h.robot_time, list(h.prims.executed), [d for _, d in h.wires['setpoint'].sent]
    first = cancelled()
    assert first[0] == 'preempted'
    assert cancelled() == first


def test_the_robot_stands_still_while_a_consumer_taking_part_works():
    steps = []
    cond = threading.Condition()

    def cycle():
        steps.append(clock())
        clock.advance()
        clock.wake()
    clock = Lockstep(1.0, 0.1, cycle)
    thread = threading.Thread(target=clock.robot_loop, daemon=True)
    thread.start()
    try:
        with clock.taking_part():
            before = clock()
            sum(range(200000))                      # work on a state: no cycle meanwhile
            assert clock() == before and steps == []
            with cond:
                clock.wait(cond)                    # waiting: exactly one cycle
            assert steps == [1.0] and clock() == 1.1
            with cond:
                clock.wait(cond)
            assert steps == [1.0, 1.1]
    finally:
        clock.close()
        thread.join(5.0)
    assert not thread.is_alive()
