"""The twin's cameras: MuJoCo's offscreen renderer, lit by the robot's LEDs only.

The front camera sits on the pan/tilt (board 20), the rear camera is fixed
in the rear module (pirate.sim.twin_robot). While rendering, the room light
and MuJoCo's headlight are off, the LED lights (front: board 21, rear:
board 28) shine as bright as the board's duty says, the walls are opaque
and the robot's own shells are hidden (the lens looks out of the dome).

Headless: the GL context is EGL, or OSMesa where there is no EGL library,
or what ``MUJOCO_GL`` names (egl, osmesa, glfw); made here, whatever
``MUJOCO_GL`` was when MuJoCo was first imported. A GL context belongs to
the thread that made it: make and use a :class:`TwinCameras` in one thread.
"""
import ctypes.util
import os

import mujoco
import numpy

from pirate.robot import safety
from pirate.sim import twin_model, twin_pipes, twin_robot

CAMERAS = {'front': twin_robot.FRONT_CAMERA, 'rear': twin_robot.REAR_CAMERA}
#: Each LED light of the model and the setpoint element (pirate.robot.tables) that drives it.
LEDS = {twin_robot.FRONT_LED: 'front_led', twin_robot.REAR_LED: 'rear_led'}
ROBOT_GROUP = 0                 # the robot's shells and wheels (twin_model defaults)
LED_FULL_DIFFUSE = 1.0          # a light's diffuse colour at full duty
LED_SPECULAR = 0.3              # a light's specular colour at full duty: a faint sheen on the wet-looking wall
LED_SCATTERED = 0.25            # ambient share at full duty: LED light the pipe's walls throw back
#: Software GL (Mesa's llvmpipe behind EGL on a machine without a GPU) spends
#: most of a frame on multisampling and on each box face's 4 x 4 quads: one
#: sample and one quad per face cut a frame from 4-10 ms to 1.5-3 ms
#: (measurements.md#twin-camera-cost). The lighting is per vertex, so a
#: long wall is lit from its ends.
OFFSCREEN_SAMPLES = 0
QUADS_PER_FACE = 1
#: Walls and defects further from the lens than this are left out of a frame:
#: estimate of what the LEDs light enough to be seen; each geom drawn costs.
VIEW_RANGE_M = 1.5
HIDDEN_GROUP = 5                # a geom group no camera draws
NEAR_CLIP_M = 0.002             # nearest wall a lens sees (a wall 23 mm below the lens is in view)


def gl_backend():
    """The GL back end the cameras use: ``MUJOCO_GL`` if set, else EGL if its library is there, else OSMesa."""
    return os.environ.get('MUJOCO_GL') or ('egl' if ctypes.util.find_library('EGL') else 'osmesa')


def gl_context(width, height):
    """A current offscreen GL context of the back end :func:`gl_backend` names."""
    backend = gl_backend()
    if backend == 'egl':
        from mujoco.egl import GLContext
    elif backend == 'osmesa':
        from mujoco.osmesa import GLContext
    else:
        from mujoco.glfw import GLContext
    context = GLContext(width, height)
    context.make_current()
    return context


def led_level(counts):
    """Brightness 0..1 of an LED driven at ``counts`` (PWM duty; None: board stopped)."""
    return 0.0 if counts is None else min(1.0, abs(float(counts)) / safety.DUTY_MAX)


class TwinCameras(object):
    """Renders the twin's cameras as ``height`` x ``width`` RGB arrays."""

    def __init__(self, twin, width, height):
        self.twin, self.model = twin, twin.model
        self.width, self.height = width, height
        self.model.vis.quality.offsamples = OFFSCREEN_SAMPLES
        self.model.vis.quality.numquads = QUADS_PER_FACE
        self.model.vis.global_.offwidth = max(width, self.model.vis.global_.offwidth)
        self.model.vis.global_.offheight = max(height, self.model.vis.global_.offheight)
        self._context = gl_context(width, height)
        self._mjr = mujoco.MjrContext(self.model, mujoco.mjtFontScale.mjFONTSCALE_100)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, self._mjr)
        self._scene = mujoco.MjvScene(self.model, maxgeom=self.model.ngeom + 100)
        self._camera = mujoco.MjvCamera()
        self._camera.type = mujoco.mjtCamera.mjCAMERA_FIXED
        self._rect = mujoco.MjrRect(0, 0, width, height)
        self._pixels = numpy.empty((height, width, 3), numpy.uint8)
        self._option = mujoco.MjvOption()
        self._option.geomgroup[ROBOT_GROUP] = 0
        self.model.vis.map.znear = NEAR_CLIP_M / self.model.stat.extent     # MuJoCo's is relative to the model
        self._lights = {name: self.model.light(name).id for name in LEDS}
        self._room = self.model.light(twin_model.ROOM_LIGHT).id
        groups = self.model.geom_group
        self._walls = numpy.flatnonzero(groups == twin_pipes.PIPE_GROUP)
        self._seen = numpy.flatnonzero((groups == twin_pipes.PIPE_GROUP) | (groups == twin_pipes.DEFECT_GROUP))
        self._option.geomgroup[HIDDEN_GROUP] = 0

    def _lit_by_leds(self, camera):
        """Set the lights and what ``camera`` can see; return what to restore for the viewers."""
        model = self.model
        saved = (model.light_active.copy(), model.light_diffuse.copy(), model.light_specular.copy(),
                 model.light_ambient.copy(),
                 model.vis.headlight.active, model.geom_rgba[self._walls, 3].copy(), model.geom_group.copy())
        lens = self.twin.data.cam_xpos[model.camera(CAMERAS[camera]).id]
        far = numpy.linalg.norm(self.twin.data.geom_xpos[self._seen] - lens, axis=1) - model.geom_rbound[self._seen]
        model.geom_group[self._seen[far > VIEW_RANGE_M]] = HIDDEN_GROUP
        model.light_active[self._room] = 0
        model.vis.headlight.active = 0
        for light, element in LEDS.items():
            level = led_level(self.twin.led_drive(element))
            model.light_active[self._lights[light]] = 1     # with no light on, GL's own ambient would light the scene
            model.light_diffuse[self._lights[light]] = LED_FULL_DIFFUSE * level
            model.light_specular[self._lights[light]] = LED_SPECULAR * level
            model.light_ambient[self._lights[light]] = LED_SCATTERED * level
        model.geom_rgba[self._walls, 3] = 1.0
        return saved

    def _restore(self, saved):
        model = self.model
        model.light_active[:], model.light_diffuse[:], model.light_specular[:], model.light_ambient[:] = saved[:4]
        model.vis.headlight.active = saved[4]
        model.geom_rgba[self._walls, 3] = saved[5]
        model.geom_group[:] = saved[6]

    def render(self, camera):
        """The image of ``camera`` ('front' or 'rear') now: uint8 (height, width, 3)."""
        if camera not in CAMERAS:
            raise KeyError('no camera %r; the twin has %s' % (camera, ', '.join(sorted(CAMERAS))))
        saved = self._lit_by_leds(camera)
        try:
            self._context.make_current()
            self._camera.fixedcamid = self.model.camera(CAMERAS[camera]).id
            mujoco.mjv_updateScene(self.model, self.twin.data, self._option, None, self._camera,
                                   mujoco.mjtCatBit.mjCAT_ALL, self._scene)
            mujoco.mjr_render(self._rect, self._scene, self._mjr)
            mujoco.mjr_readPixels(self._pixels, None, self._rect, self._mjr)
            return numpy.flipud(self._pixels).copy()       # GL's rows run bottom up
        finally:
            self._restore(saved)

    def close(self):
        """Free the GL resources (in the thread that made them)."""
        self._mjr.free()
        self._context.free()
