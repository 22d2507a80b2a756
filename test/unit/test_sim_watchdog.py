"""The simulated robot has the firmware's Mega watchdog.

Before, the simulated robot kept executing after the manager died, unlike
the firmware (firmware/PirateBay/bridge.h: no setpoint array for 250 ms ->
every board STOP, until a new setpoint array).
"""
from pirate.robot import tables
from pirate.testing.harness import SimHarness
from pirate.sim.watchdog import WATCHDOG_S, MegaWatchdog

STOP, PLAY = 8, 7
COMMAND = tables.element('rear_module').index


def test_watchdog_arms_on_a_setpoint_and_trips_after_its_timeout():
    dog = MegaWatchdog()
    modes = [0] * tables.CONTROL_SIZE
    modes[COMMAND] = PLAY
    assert dog.boards_see(modes)[COMMAND] == STOP          # after power-up: STOP
    dog.setpoint_arrived(10.0)
    assert dog.boards_see(modes)[COMMAND] == PLAY
    assert not dog.poll(10.0 + WATCHDOG_S)
    assert dog.poll(10.0 + WATCHDOG_S + 0.01) and dog.trips == 1
    assert dog.boards_see(modes)[COMMAND] == STOP
    assert not dog.poll(20.0)                              # trips once
    dog.setpoint_arrived(20.0)
    assert dog.boards_see(modes)[COMMAND] == PLAY and modes[COMMAND] == PLAY


def test_the_simulated_robot_stops_when_the_setpoint_stream_stops():
    """The manager dies mid-drive: the wheels stop within the watchdog, no STOP sent."""
    with SimHarness() as h:
        h.start_robot()
        h.control.set_mode('wheels', 'velocity')
        h.setpoint.set('wheels', 20)
        assert h.wait_robot(lambda: h.wheel_mm_s() > 10.0, 5.0), h.wheel_mm_s()       # unclamped, on the floor
        h.setpoint.enabled = False                 # the 10 Hz stream ends: the manager is gone
        stopped_at = h.robot_time
        assert h.wait_robot(lambda: not h.model.running, WATCHDOG_S + 1.0)
        assert h.robot_time - stopped_at <= WATCHDOG_S + 0.1 + 1e-9     # within the next Mega cycle
        assert h.watchdog.trips == 1
        assert h.wait_robot(lambda: h.wheel_mm_s() < 1.0, 2.0), h.wheel_mm_s()
