"""The findings recorder: what the inspection node knows, and a mark. Pure.

It keeps the latest of everything a finding needs: the robot's state (the
front camera's pan and tilt, the rear part's roll, the odometry), the
mission executive's estimate along the map with its uncertainty, and each
camera's frame. :meth:`Recorder.mark` turns them into a finding in the
run's store (pirate.inspection.store), frames first.

Where the robot is: the mission's estimate when one arrives (each one
re-anchors the recorder's dead reckoning), followed between estimates and
without a mission by the odometry from that anchor, the uncertainty
growing by the localiser's drift (config/supervisory.yaml
``odometry_drift``). Before any estimate the anchor is the launch pit, with
the localiser's tolerance as its uncertainty.

The missions heard (goal, each step as it starts or waits, the result) go
into the run's timeline (``timeline.jsonl``) with their robot time.
"""
import collections
import datetime

from pirate.inspection import findings as fd
from pirate.inspection import frames

CAMERAS = ('front', 'rear')
#: The latest frame of a camera: the fields of a sensor_msgs/Image and its stamp (s).
Frame = collections.namedtuple('Frame', 'width height encoding step data stamp_s')
#: Where the recorder's dead reckoning starts: m along, odometry mm (None: the next reading), m uncertain.
Anchor = collections.namedtuple('Anchor', 'along_m odometry_mm uncertainty_m')


class Recorder(object):
    """Marks findings into a :class:`pirate.inspection.store.RunStore`."""

    def __init__(self, run, settings):
        """``settings``: config/supervisory.yaml (locate_tolerance_mm, odometry_drift)."""
        self.run = run
        self._tolerance_m = settings['locate_tolerance_mm'] / 1000.0
        self._drift = settings['odometry_drift']
        self.pipe_map = self.launch_m = self.anchor = None
        self.joints, self.roll, self.odometry_mm = {}, fd.UPRIGHT_RAD, None
        self._uncertainty_m = self._tolerance_m
        self.frames = {}
        self._mission_step = None
        self._estimated = False         # the anchor is the mission's estimate, not the launch pit

    # --- what the node hears ------------------------------------------------
    def set_map(self, pipe_map, launch_m):
        """The map of the job and the launch pit on it (m along); the robot
        is taken to be at the launch pit until an estimate says otherwise (an
        estimate heard before the map, on the same map, stands)."""
        same = self.pipe_map is None or self.pipe_map.source == pipe_map.source
        self.pipe_map, self.launch_m = pipe_map, launch_m
        if not (self._estimated and same):      # an estimate on this map stands
            self.anchor = Anchor(launch_m, self.odometry_mm, self._tolerance_m)
            self._estimated = False

    def robot_state(self, joint_names, positions, roll_rad, odometry_mm):
        """One RobotState: joints (rad), roll (rad, Fig 4.7), odometry (mm)."""
        self.joints = dict(zip(joint_names, positions))
        self.roll, self.odometry_mm = roll_rad, odometry_mm
        if self.anchor is not None and self.anchor.odometry_mm is None:
            self.anchor = self.anchor._replace(odometry_mm=odometry_mm)

    def uncertainty(self, uncertainty_mm):
        """The mission's uncertainty (mm): of its estimate now, whichever of
        the two arrives first, and of the next."""
        self._uncertainty_m = uncertainty_mm / 1000.0
        if self.anchor is not None:
            self.anchor = self.anchor._replace(uncertainty_m=self._uncertainty_m)

    def estimate(self, along_mm):
        """The mission's estimate (mm along the map): re-anchors here."""
        self.anchor = Anchor(along_mm / 1000.0, self.odometry_mm, self._uncertainty_m)
        self._estimated = True

    def mission_goal(self, stamp_s, map_name, points, mission_id):
        """A mission was accepted (``stamp_s``; ``mission_id`` its goal id):
        into the timeline, once however often it is heard."""
        self._mission_step = None
        self.run.log_mission({'stamp_s': stamp_s, 'text': 'mission sent: %s, %s' % (map_name, ' -> '.join(points))},
                             mission_id)

    def mission_feedback(self, stamp_s, step, steps, pab, option, along_mm, state, waiting_for):
        """A mission's feedback: into the timeline when its step or state changes."""
        key = (step, state, waiting_for)
        if key == self._mission_step:
            return
        self._mission_step = key
        text = 'step %d/%d: %s%s, %s%s' % (step, steps, pab, ' ' + option if option else '', state,
                                           ' for ' + waiting_for if waiting_for else '')
        self.run.log_event({'stamp_s': stamp_s, 'text': text, 'along_mm': round(along_mm, 1)})

    def mission_result(self, stamp_s, status, message):
        """A mission's end: into the timeline."""
        self._mission_step = None
        along_m = self.where()[0] if self.anchor is not None else None
        event = {'stamp_s': stamp_s, 'text': 'mission %s: %s' % (status, message)}
        if along_m is not None:
            event['along_mm'] = round(along_m * 1000, 1)
        self.run.log_event(event)

    def frame(self, camera, frame):
        """The latest :data:`Frame` of ``camera`` (one of :data:`CAMERAS`)."""
        self.frames[camera] = frame

    def forget_frames(self):
        """No camera has a frame until the next :meth:`frame` (a mark keeps none of the last one's)."""
        self.frames = {}

    # --- the mark -------------------------------------------------------------
    def where(self):
        """(m along the map, m uncertain) now, from the anchor and the odometry since."""
        if self.anchor is None or self.pipe_map is None:       # anchored by the executive before the map came
            raise fd.FindingError('no map: start a mission or give the inspection node a map (~map)')
        travelled_m = 0.0
        if self.anchor.odometry_mm is not None and self.odometry_mm is not None:
            travelled_m = (self.odometry_mm - self.anchor.odometry_mm) / 1000.0
        return self.anchor.along_m + travelled_m, self.anchor.uncertainty_m + self._drift * abs(travelled_m)

    def mark(self, kind, note, stamp_s, source, now=None, where=None):
        """Record a finding (``stamp_s``: robot time, s; ``source``: who
        marked it; ``where``: :meth:`where` when it was marked, default now);
        the finding as stored. :class:`fd.FindingError` when it cannot be
        placed."""
        kind = fd.check_kind(kind)
        along_m, uncertainty_m = where or self.where()
        position = fd.position_on_map(self.pipe_map, along_m, self.launch_m, uncertainty_m,
                                      self.joints.get('camera_pan', 0.0), self.joints.get('camera_tilt', 0.0),
                                      self.roll)
        number = self.run.next_number()
        saved, missing = {}, {}
        for camera in CAMERAS:
            try:
                saved[camera] = self._save(number, camera)
            except (KeyError, frames.FrameError) as why:
                missing[camera] = 'no frame: %s' % (why if isinstance(why, frames.FrameError) else 'none received')
        finding = {'number': number, 'kind': kind, 'note': note, 'source': source, 'stamp_s': stamp_s,
                   'wall_time': (now or datetime.datetime.utcnow()).strftime('%Y-%m-%dT%H:%M:%SZ'),
                   'position': position, 'frames': saved, 'no_frame': missing,
                   'frame_stamps_s': {c: self.frames[c].stamp_s for c in saved},
                   'robot': {'odometry_mm': self.odometry_mm, 'roll_rad': self.roll,
                             'camera_pan_rad': self.joints.get('camera_pan'),
                             'camera_tilt_rad': self.joints.get('camera_tilt')}}
        return self.run.append(finding)

    def _save(self, number, camera):
        got = self.frames[camera]
        png = frames.png_of(got.width, got.height, got.encoding, got.step, got.data)
        return self.run.save_frame(number, camera, png)
