"""The twin's cameras: rendered headless, lit by the LEDs only, moved by
the pan/tilt commands, showing the world's defects; published as
sensor_msgs/Image + CameraInfo in the camera's optical frame, stamped on
the robot's clock, only while someone watches. Small images (64 x 48)."""
import xml.etree.ElementTree as ET

import numpy
import pytest
import yaml
from rospy import Time

from pirate import names
from pirate.camera.images_ros import CameraStreams
from pirate.robot import safety, tables, units
from pirate.sim import twin, twin_camera, twin_model
from pirate.world import network

WIDTH, HEIGHT = 64, 48
RUST = ('corrosion', 12)          # the defect the front camera looks at: a rust patch at 12 o'clock


def _world(defects=()):
    return network.build({'name': 'camera_test', 'pieces': [{'type': 'straight', 'length_mm': 1200}, {'type': 'cap'}],
                          'start': {'at_mm': 500}, 'defects': list(defects)}, source='camera_test')


def _lit(robot, front=safety.DUTY_MAX, rear=safety.DUTY_MAX, pan_rad=None):
    """Boards playing, LEDs at ``front`` / ``rear`` duty, the pan held in position mode."""
    setpoints, modes = [0] * tables.SETPOINT_SIZE, list(robot.modes)
    modes[tables.element('rear_module').index] = safety.COMMAND_CODES['play']
    setpoints[tables.element('front_led').index] = front
    setpoints[tables.element('rear_led').index] = rear
    if pan_rad is not None:
        modes[tables.element('camera_pan').index] = safety.MODE_CODES['position']
        setpoints[tables.element('camera_pan').index] = units.rad_to_encoder(pan_rad)
    robot.command(setpoints, modes, robot.limits)
    robot.step(twin.PICO_PERIOD_S)


def _cameras(defects=()):
    robot = twin.TwinRobot(_world(defects), settle_s=0.05)
    return robot, twin_camera.TwinCameras(robot, WIDTH, HEIGHT)


def _rusty(pixels):
    """Pixels clearly redder than the pipe's blue-grey wall."""
    red, green, blue = (pixels[..., k].astype(int) for k in range(3))
    return int(numpy.count_nonzero((red > green + 15) & (red > blue + 15)))


@pytest.fixture(scope='module')
def rusty_pipe():
    """A rust patch at 12 o'clock 120 mm ahead of the front camera (at 797 mm)."""
    robot, cameras = _cameras([{'type': RUST[0], 'segment': 0, 'at_mm': 920, 'clock': RUST[1], 'size_mm': 40}])
    _lit(robot)
    yield robot, cameras
    cameras.close()


def test_both_cameras_render_an_image_of_the_asked_size(rusty_pipe):
    _, cameras = rusty_pipe
    for camera in ('front', 'rear'):
        pixels = cameras.render(camera)
        assert pixels.shape == (HEIGHT, WIDTH, 3) and pixels.dtype == numpy.uint8
        assert pixels.mean() > 10, '%s camera sees nothing with its LEDs on' % camera


def test_a_defect_ahead_appears_in_the_front_image_and_not_without_it(rusty_pipe):
    _, cameras = rusty_pipe
    assert _rusty(cameras.render('front')) > 10
    robot, plain = _cameras()
    _lit(robot)
    assert _rusty(plain.render('front')) == 0
    plain.close()


def test_the_rear_camera_looks_the_other_way(rusty_pipe):
    _, cameras = rusty_pipe
    assert _rusty(cameras.render('rear')) == 0


def test_with_the_leds_off_the_cameras_see_nothing():
    robot, cameras = _cameras()
    _lit(robot, front=0, rear=0)
    dark = {camera: cameras.render(camera) for camera in ('front', 'rear')}
    _lit(robot)
    lit = {camera: cameras.render(camera) for camera in ('front', 'rear')}
    cameras.close()
    for camera in ('front', 'rear'):
        assert dark[camera].max() <= 2, '%s: light other than the LEDs' % camera
        assert lit[camera].mean() > 10


def test_each_led_lights_its_own_camera():
    robot, cameras = _cameras()
    _lit(robot, front=safety.DUTY_MAX, rear=0)
    front_only = cameras.render('front').mean(), cameras.render('rear').mean()
    cameras.close()
    assert front_only[0] > 10 and front_only[1] < front_only[0] / 2


def test_panning_the_front_camera_moves_the_defect_out_of_view():
    robot, cameras = _cameras([{'type': RUST[0], 'segment': 0, 'at_mm': 920, 'clock': RUST[1], 'size_mm': 40}])
    _lit(robot, pan_rad=0.0)
    ahead = cameras.render('front')
    _lit(robot, pan_rad=1.2)
    robot.step(1.0)                 # the pan turns at its drive's speed
    panned = cameras.render('front')
    cameras.close()
    assert abs(robot.angle('camera_pan') - 1.2) < 0.05
    assert _rusty(ahead) > 10 and _rusty(panned) < _rusty(ahead) / 2


class FakePublisher(object):
    def __init__(self, connections=1):
        self.connections, self.sent = connections, []

    def get_num_connections(self):
        return self.connections

    def publish(self, msg):
        self.sent.append(msg)


def test_published_images_carry_the_optical_frame_and_the_robot_clock_stamp(rusty_pipe):
    _, cameras = rusty_pipe
    pubs = {camera: (FakePublisher(), FakePublisher()) for camera in ('front', 'rear')}
    streams = CameraStreams(pubs, cameras.render, 0.1, 90.0)
    assert streams.tick(12.34, Time.from_sec(12.34)) == ['front', 'rear']
    for camera, (image_pub, info_pub) in pubs.items():
        image, info = image_pub.sent[0], info_pub.sent[0]
        assert image.header.frame_id == info.header.frame_id == names.CAMERA_FRAMES[camera]
        assert image.header.stamp == info.header.stamp == Time.from_sec(12.34)
        assert (image.width, image.height, image.encoding, image.step) == (WIDTH, HEIGHT, 'rgb8', WIDTH * 3)
        assert len(image.data) == WIDTH * HEIGHT * 3
        assert (info.width, info.height) == (WIDTH, HEIGHT)
        assert info.K[0] == pytest.approx(HEIGHT / 2.0)      # 90 deg vertical field of view


def test_images_come_at_the_rate_and_only_while_watched():
    rendered = []
    pubs = {'front': (FakePublisher(0), FakePublisher(0)), 'rear': (FakePublisher(0), FakePublisher(1))}
    streams = CameraStreams(pubs, lambda camera: rendered.append(camera) or numpy.zeros((2, 2, 3), numpy.uint8),
                            0.1, 90.0)
    published = [streams.tick(k * 0.02, Time.from_sec(k * 0.02)) for k in range(11)]     # 0.2 s of PICO samples
    assert rendered == ['rear', 'rear', 'rear']          # at 0, 0.1, 0.2 s; the front nobody watches
    assert [k for k, cams in enumerate(published) if cams] == [0, 5, 10]


def _inspection_world(start_mm):
    """inspection_network_90 with the robot's middle at ``start_mm``."""
    with open(network.world_path('inspection_network_90')) as stream:
        data = yaml.safe_load(stream)
    data['start'] = {'at_mm': start_mm}
    return network.build(data, source='inspection_network_90')


def test_the_rear_camera_finds_the_deposit_past_the_last_bend_on_the_way_back():
    world = _inspection_world(4320)          # on the way back from the target, rear camera leading
    deposit, = [d for d in world.defects if d.kind == 'deposit']
    robot = twin.TwinRobot(world, settle_s=0.05)
    cameras = twin_camera.TwinCameras(robot, WIDTH, HEIGHT)
    _lit(robot)
    rear = cameras.render('rear')
    cameras.close()
    assert 0.1 < 4.32 - 0.3 - deposit.along < 0.2      # the deposit lies 100-200 mm behind the rear camera
    red, blue = rear[..., 0].astype(int), rear[..., 2].astype(int)
    assert numpy.count_nonzero(red > blue + 10) > 5, 'the rear camera does not see the deposit'


@pytest.mark.parametrize('kind', sorted(network.DEFECT_KEYS))
def test_every_defect_kind_is_drawn_and_touches_nothing(kind):
    world = _world([{'type': kind, 'segment': 0, 'at_mm': 900, 'clock': 3, 'size_mm': 10}])
    root = ET.fromstring(twin_model.model_xml(world, twin_model.load_config(), 1.5708))
    geoms = [g for g in root.iter('geom') if g.get('name', '').startswith('defect_' + kind)]
    assert geoms and all(g.get('contype') == g.get('conaffinity') == '0' for g in geoms)
