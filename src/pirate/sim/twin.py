"""PIRATE as a rigid-body robot in a pipe network (MuJoCo), standing in
for serial link, Mega, the nine PICO boards and the robot.

Same interface as every simulated robot end: :meth:`command` takes the
three arrays as the Mega receives them, :meth:`step` advances the physics,
:meth:`small_state` gives a board's raw Table B.1 elements, computed only
from what that board senses (AS5055 angles, spring encoder, wheel
encoders, motor current, the IMU). :meth:`ground_truth` is for tests,
benchmarks and RViz; no PAB may read it.
"""
import math
import random

import mujoco
import numpy

from pirate.robot import safety, tables, units
from pirate.sim import boards, twin_model, twin_robot, twin_start
from pirate.sim.latch import CODE, CommandLatch
from pirate.world import network

PICO_PERIOD_S = 0.02
SETTLE_S = 0.5            # physics before the clock starts: the robot comes to rest
ANGLE_BOARDS = {j.board: j.name for j in tables.JOINTS if j.board is not None and j.name != 'rotation'}


class TwinRobot(CommandLatch):
    """The physics twin. ``world``: a Network or a world file path."""

    def __init__(self, world, orientation=math.pi / 2, joints=None, seed=None, config=None, settle_s=SETTLE_S):
        CommandLatch.__init__(self)
        self.world = network.load(world) if isinstance(world, str) else world
        self.config = config or twin_model.load_config()
        self.model = mujoco.MjModel.from_xml_string(twin_model.model_xml(self.world, self.config, orientation))
        self.data = mujoco.MjData(self.model)
        self.pipe_diameter_m = twin_model.bore_at(self.world, self.config, self.world.start_m)   # where the walls are
        self._rng = random.Random(seed) if seed is not None and seed >= 0 else None
        self._bias = _biases(seed, self.config['sensors']['angle_bias_counts'])
        self._qadr = {name: self.model.jnt_qposadr[self.model.joint(name).id] for name in twin_robot.chain_joints()}
        self._dofadr = {name: self.model.jnt_dofadr[self.model.joint(name).id] for name in twin_robot.chain_joints()}
        self._pose(joints, orientation)
        self._actuator = {name: self.model.actuator(name).id for name in twin_model.actuator_names()}
        self._make_boards()
        self._ctrl()
        self._substeps = int(round(PICO_PERIOD_S / self.model.opt.timestep))
        self._settle(settle_s)
        self.rotation_board.zero = self.angle('rotation')
        self.time = 0.0

    def _pose(self, joints, roll):
        """The start ``joints`` set, the robot moved across the pipe to where
        they fit (:mod:`pirate.sim.twin_start`); raises StartPoseError."""
        _, frame = self.world.locate(self.world.start_m)
        inside_m = self.pipe_diameter_m / 2 - self.config['geometry']['body_radius_m']
        try:
            twin_start.place(self.model, self.data, joints, twin_robot.ROOT_JOINT,
                             (numpy.asarray(frame.origin), frame.axes[1:3], inside_m),
                             stops={'front_tilt': self.config['front_tilt']['range_rad']})
        except twin_start.StartPoseError as refused:
            raise twin_start.StartPoseError('%s (world %s, %.0f mm, roll %.2f rad)' % (
                refused, self.world.name, self.pipe_diameter_m * 1000, roll))

    def _make_boards(self):
        cfg = self.config
        self.bend_boards = {name: boards.BendBoard(cfg['bend'], self.angle(name)) for name in tables.BEND_JOINTS}
        self.gear_boards = {'front_tilt': boards.GearBoard(cfg['front_tilt'], self.angle('front_tilt'))}
        for name in ('camera_tilt', 'camera_pan'):
            self.gear_boards[name] = boards.GearBoard(cfg['camera'], self.angle(name))
        self.rotation_board = boards.RotationBoard(cfg['rotation'], self.angle('rotation'))
        radius = cfg['geometry']['wheel_diameter_m'] / 2
        self.wheel_boards = {b: boards.WheelBoard(cfg['wheel'], radius, tables.WHEEL_SIGN[b])
                             for b in tables.DRIVE_BOARDS}
        self._wheel_targets = {b: (0.0, w.motor_kv) for b, w in self.wheel_boards.items()}

    def _settle(self, seconds):
        for _ in range(int(seconds / self.model.opt.timestep)):
            mujoco.mj_step(self.model, self.data)

    # --- what the robot's own sensors see -------------------------------
    def angle(self, joint):
        """True joint angle, rad (what an ideal encoder reads)."""
        return float(self.data.qpos[self._qadr[joint]])

    def rate(self, joint):
        return float(self.data.qvel[self._dofadr[joint]])

    # --- boards ------------------------------------------------------------
    def _limit(self, name):
        limit = self.limits[tables.limit_index(name)]
        return None if self.no_limits or limit == safety.NO_LIMIT else limit

    def _mode_of(self, name):
        index = tables.element(name).index
        return self.modes[index] if index < tables.CONTROL_SIZE else CODE['pwm']

    def _boards(self, dt):
        """Every board's loop, one PICO sample."""
        for name, board in self.bend_boards.items():
            board.update(self._mode_of(name), self._drive(name), self._limit(name), self.angle(name), dt)
        for name, board in self.gear_boards.items():
            board.update(self._mode_of(name), self._drive(name), self.angle(name), dt)
        self.rotation_board.update(self._mode_of('rotation'), self._drive('rotation'), dt)
        counts, mode = self._drive('wheels'), self._mode_of('wheels')
        for board, wheel in self.wheel_boards.items():
            self._wheel_targets[board] = wheel.update(mode, counts, self.rate(twin_robot.wheel_joint(board)), dt)
        self._ctrl()

    def _ctrl(self):
        ctrl, act_id = self.data.ctrl, self._actuator
        for name, board in self.bend_boards.items():
            ctrl[act_id[name]] = board.worm
        for name, board in self.gear_boards.items():
            ctrl[act_id[name]] = board.angle
        ctrl[act_id['rotation']] = self.rotation_board.target
        for board, (target, kv) in getattr(self, '_wheel_targets', {}).items():
            act = act_id[twin_robot.wheel_joint(board)]
            ctrl[act] = target
            self.model.actuator_gainprm[act, 0] = kv       # a velocity servo: kv (ctrl - qdot)
            self.model.actuator_biasprm[act, 2] = -kv

    def step(self, dt):
        """Advance ``dt`` seconds: the boards every PICO sample, physics between."""
        samples = max(1, int(round(dt / PICO_PERIOD_S)))
        for _ in range(samples):
            self._boards(PICO_PERIOD_S)
            mujoco.mj_step(self.model, self.data, nstep=self._substeps)   # the steps between two PICO samples
            self.time += PICO_PERIOD_S

    def led_drive(self, name):
        """The duty an LED element ('front_led', 'rear_led') is driven at; None while its board is stopped."""
        return self._drive(name)

    # --- Small State (Table B.1), raw ----------------------------------------
    def _noise(self, sigma):
        return self._rng.gauss(0.0, sigma) if self._rng else 0.0

    def _encoder(self, joint):
        noise = self._noise(self.config['sensors']['angle_noise_counts']) + self._bias.get(joint, 0.0)
        return units.rad_to_encoder(self.angle(joint)) + int(round(noise))

    def _wheel_elements(self, board, data):
        wheel = self.wheel_boards[board]
        joint = twin_robot.wheel_joint(board)
        travel_mm = wheel.sign * self.angle(joint) * wheel.radius * 1000.0
        data[tables.SS_ODOMETRY] = units.wrap_int16(int(round(travel_mm / units.WHEEL_MM_PER_COUNT)))
        data[tables.SS_VELOCITY] = units.mm_s_to_wheel_counts(wheel.sign * self.rate(joint) * wheel.radius * 1000.0)
        force = self.data.actuator_force[self._actuator[joint]]
        data[tables.SS_DRIVE_LOAD] = int(round(wheel.sign * force / self.config['wheel']['stall_nm'] * safety.DUTY_MAX))

    def _imu_elements(self, data):
        """Accelerometer (gravity's up in the rear part's frame) and gyro."""
        rot = self.data.body(twin_robot.ROOT).xmat.reshape(3, 3)
        up = rot.T @ numpy.array((0.0, 0.0, 1.0))
        sigma = self.config['sensors']['imu_noise_counts']
        for index, g in zip((tables.SS_IMU_X, tables.SS_IMU_Y, tables.SS_IMU_Z), up):
            data[index] = int(round(g * units.IMU_COUNTS_PER_G + self._noise(sigma)))
        for index, w in zip((tables.SS_IMU_U, tables.SS_IMU_V, tables.SS_IMU_W), self.gyro()):
            data[index] = int(round(math.degrees(w) * units.IMU_COUNTS_PER_DEG_S))

    def gyro(self):
        """Angular velocity of the rear part in its own frame, rad/s (the
        free joint's rotational dofs; debris bodies have free joints too)."""
        start = self.model.jnt_dofadr[self.model.joint(twin_robot.ROOT_JOINT).id] + 3
        return self.data.qvel[start:start + 3]

    def small_state(self, board):
        """The nine raw int16 elements of ``board``'s Small State (Table B.1)."""
        if board not in tables.BOARDS:
            raise KeyError('no PICO board %r' % board)
        data = [0] * tables.SMALL_STATE_SIZE
        if board in tables.DRIVE_BOARDS:
            self._wheel_elements(board, data)
        if board == tables.IMU_BOARD:
            self._imu_elements(data)
            return [units.wrap_int16(v) for v in data]
        if board == tables.ROTATION_BOARD:
            data[tables.SS_ANGLE] = units.rad_to_rotation(self.angle('rotation') - self.rotation_board.zero)
        elif board in ANGLE_BOARDS:
            name = ANGLE_BOARDS[board]
            data[tables.SS_ANGLE] = self._encoder(name)
            if name in self.bend_boards:
                bend = self.bend_boards[name]
                data[tables.SS_BEND_LOAD] = bend.spring_counts(self.angle(name))
                data[tables.SS_TORQUE] = int(round(bend.duty))
        return [units.wrap_int16(v) for v in data]

    # --- ground truth (tests, bench, RViz only) ------------------------------
    def body_pose(self, name):
        """(position, quaternion w x y z) of a body in the world."""
        body = self.data.body(name)
        return tuple(float(v) for v in body.xpos), tuple(float(v) for v in body.xquat)

    @property
    def rear_roll(self):
        """True roll of the rear part, rad (Fig 4.7)."""
        return self.roll()

    def roll(self, body=twin_robot.ROOT):
        """True roll of a body about its own x axis (Fig 4.7)."""
        rot = self.data.body(body).xmat.reshape(3, 3)
        up = rot.T @ numpy.array((0.0, 0.0, 1.0))
        return units.gravity_to_roll(up[1], up[2])

    def wheel_contacts(self):
        """{wheel board: normal force (N)} of wheels touching the pipe."""
        forces = {}
        wrench = numpy.zeros(6)
        for i in range(self.data.ncon):
            contact = self.data.contact[i]
            for geom in (contact.geom1, contact.geom2):
                name = self.model.geom(geom).name
                if name.startswith('wheel_geom_'):
                    mujoco.mj_contactForce(self.model, self.data, i, wrench)
                    board = int(name.rsplit('_', 1)[1])
                    forces[board] = forces.get(board, 0.0) + abs(float(wrench[0]))
        return forces

    def ground_truth_poses(self):
        """[(position, quaternion w x y z)] of twin_robot.TRUTH_BODIES, world frame."""
        return [self.body_pose(name) for name in twin_robot.TRUTH_BODIES]

    def ground_truth(self):
        """True pose of every module, wheel contacts, travel along the network."""
        return {'time': self.time, 'poses': dict(zip(twin_robot.TRUTH_BODIES, self.ground_truth_poses())),
                'wheel_contacts': self.wheel_contacts(), 'roll': self.roll(),
                'front_roll': self.roll(twin_robot.ROTATIONAL_FRONT)}


def _biases(seed, bound_counts):
    """{joint: counts} each AS5055's constant offset, drawn from ``seed``
    within +-``bound_counts`` (its own generator, so the noise stays as
    before); none without a seed."""
    if seed is None or seed < 0 or not bound_counts:
        return {}
    rng = random.Random('angle bias %d' % seed)
    return {joint.name: rng.uniform(-bound_counts, bound_counts) for joint in tables.JOINTS
            if joint.angle_unit == tables.ENCODER and joint.board is not None}
