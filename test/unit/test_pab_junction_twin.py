"""Take T-joint in the physics twin (issue 10.5), in process (SimHarness).

Clamped straight before a T-joint whose open side is above the robot
(config/worlds/tee_run_up_90.yaml), T_JOINT STRAIGHT senses the hole from
the front V, crosses it one part at a time and ends clamped straight with
both V's apex wheels on the wall past the hole (ground truth, read by the
test only). In a
straight pipe the same goal looks its distance, aborts with
junction_missing and leaves the robot clamped with the wheels stopped.
"""
import math

import pytest

from pirate.sequencer.pabs import codes
from pirate.sim.harness import SimHarness
from pirate.world import network
from test_sequencer_sim import SAFE_INDICES, STRAIGHT, run_bounded
from test_sim_twin_sequencer import robot_wait

SPEEDUP = 20.0
APEX_WHEELS = {23, 26}
CROSSING = ['look for the junction', 'stop wheels', 'unclamp front partial', 'drive front across', 'stop wheels',
            'clamp front', 'unclamp rear partial', 'drive rear across', 'stop wheels', 'clamp rear']
WORLDS = ('bend_down_90', 'bend_up_90', 'bend_left_90', 'bend_right_90', 'tee_run_up_90', 'tee_run_up_110',
          'tee_run_down_90', 'tees_run_up_90')


@pytest.mark.parametrize('world', WORLDS)
def test_the_junction_worlds_load(world):
    kinds = [piece.kind for piece in network.load(network.world_path(world)).pieces]
    assert kinds[0] == 'straight' and kinds[1] in ('mitre', 'tee') and kinds[-1] == 'cap'


def clamped_straight(h):
    reason, outcome = run_bounded(h, h.goal(codes.CLAMP_STRAIGHT))
    assert reason is None and outcome.status == 'succeeded', (reason, outcome and outcome.message)


def test_t_joint_straight_on_crosses_the_open_side_and_ends_clamped_past_it():
    world = network.load(network.world_path('tee_run_up_90'))
    tee = world.pieces[1]
    far_edge_x = tee.entry.origin[0] + tee.diameter      # the hole spans one diameter along the run
    with SimHarness(speedup=SPEEDUP, world='tee_run_up_90') as h:
        clamped_straight(h)
        del h.feedback[:]
        reason, outcome = run_bounded(h, h.goal(codes.T_JOINT, option=codes.STRAIGHT))
        assert reason is None and outcome.status == 'succeeded', (reason, outcome and outcome.message)
        assert h.prims.executed == CROSSING
        assert {fb.server_state for fb in h.feedback if fb.pab_state} == {'Taking T-joint'}   # Fig 4.2
        # The front V's apex starts ~310 mm before the hole; odometry also counts the clamped wheels' slip.
        assert 250.0 < outcome.junction_odometry < 500.0 and not outcome.junction_missing
        robot_wait(h, 2.0)
        truth = h.ground_truth()
        assert truth['poses']['bend_iv_module'][0][0] > far_edge_x, truth['poses']   # the rear V's apex wheel
        assert APEX_WHEELS <= set(truth['wheel_contacts'])
        assert STRAIGHT[0] <= truth['roll'] <= STRAIGHT[1]
        assert h.server.status() == 'Idle Clamped'


def test_no_junction_within_the_distance_aborts_with_junction_missing():
    with SimHarness(speedup=SPEEDUP, world='straight_90') as h:
        clamped_straight(h)
        reason, outcome = run_bounded(h, h.goal(codes.T_JOINT, option=codes.STRAIGHT, distance=150.0))
        assert reason is None and outcome.status == 'aborted'
        assert outcome.junction_missing and math.isnan(outcome.junction_odometry)
        assert 'no junction within 150 mm' in outcome.message
        sent = h.wires['setpoint'].sent[-1][1]
        assert all(sent[i] == 0 for i in SAFE_INDICES.values()), sent        # the safe hold
        assert h.server.status() == 'Idle Clamped'                            # it never let go
