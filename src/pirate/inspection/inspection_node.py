"""inspection: the findings recorder's ROS edge.

Offers ``/pirate/inspection/mark`` (pirate/InspectionMark: kind and note),
which the panel's mark button calls too; records each finding in the run
folder as it is marked (pirate.inspection.recorder, .store) and publishes
the run's findings as JSON on ``/pirate/inspection/findings`` (latched;
std_msgs/String), at start-up too, so a restarted node shows what its run
already holds.

Hears: ``/pirate/state`` (camera pan/tilt, roll, odometry), the mission's
estimate (``/pirate/mission/along_mm``, ``/pirate/mission/uncertainty_mm``),
the mission accepted last (``/pirate/mission/current``, latched, so a
recorder started late or restarted learns it: its map; the launch pit is the
map's ``launch_pit`` point, else the mission's first point), the mission's
feedback and result (the run's timeline). At each mark it takes the next frame of each camera
(``/pirate/front_camera/image_raw``, ``/pirate/rear_camera/image_raw``,
sensor_msgs/Image), subscribing only then: the twin renders a camera only
while someone subscribes, and rendering costs its real-time factor.

Params (private): ``~root`` (runs folder, default
``~/.ros/pirate/inspections``), ``~run`` (run name; default ``current``:
the run the last recorder under ``~root`` started, so a restart goes on
with it),
``~new_run`` (true: start a new run), ``~map`` (the pipe map before a
mission names one: world file or name in config/worlds/; default: the
run's, else none until a mission names one).
"""
import json
import os
import threading

import rospy
from sensor_msgs.msg import Image
from std_msgs.msg import Float64, String

from pirate import names
from pirate.inspection import findings as fd
from pirate.inspection import recorder as rec
from pirate.inspection import store
from pirate.msg import MissionActionFeedback, MissionActionGoal, MissionActionResult, RobotState
from pirate.srv import InspectionMark, InspectionMarkResponse
from pirate.supervisory.plan_cli import load_settings
from pirate.world import network

LAUNCH_PIT = 'launch_pit'
#: ``~run``: go on with the run the last recorder started; ``~map``: none until a mission names one.
CURRENT, NO_MAP = 'current', 'none'
#: Wall s a mark waits for each camera's next frame (the twin starts rendering when asked).
FRAME_WAIT_S = 3.0


class InspectionNode(object):
    """The mark service, the findings topic and what a finding needs."""

    def __init__(self):
        root = os.path.expanduser(rospy.get_param('~root', store.DEFAULT_ROOT))
        run = rospy.get_param('~run', CURRENT)
        if run in ('', CURRENT):
            run = store.current_run(root, new=bool(rospy.get_param('~new_run', False)))
        self.folder = os.path.join(root, run)
        self._lock = threading.Lock()
        self.store = store.RunStore(self.folder, {'run': run})
        for warning in self.store.warnings:
            rospy.logwarn('inspection: %s', warning)
        self.recorder = rec.Recorder(self.store, load_settings()[0])
        self._findings_pub = rospy.Publisher(names.INSPECTION_FINDINGS_TOPIC, String, queue_size=1, latch=True)
        chosen = rospy.get_param('~map', NO_MAP)
        chosen = store.read_about(self.folder).get('map') if chosen in ('', NO_MAP) else chosen
        if chosen:
            self._use_map(chosen, [])
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self._on_state, queue_size=5)
        rospy.Subscriber(names.MISSION_UNCERTAINTY_TOPIC, Float64, self._locked(
            lambda msg: self.recorder.uncertainty(msg.data)), queue_size=5)
        rospy.Subscriber(names.MISSION_ALONG_TOPIC, Float64, self._locked(
            lambda msg: self.recorder.estimate(msg.data)), queue_size=5)
        rospy.Subscriber(names.MISSION_CURRENT_TOPIC, MissionActionGoal, self._on_mission, queue_size=2)
        rospy.Subscriber(names.MISSION_ACTION + '/feedback', MissionActionFeedback, self._locked(
            lambda msg: self.recorder.mission_feedback(rospy.get_time(), *_progress(msg.feedback))), queue_size=10)
        rospy.Subscriber(names.MISSION_ACTION + '/result', MissionActionResult, self._locked(
            lambda msg: self.recorder.mission_result(rospy.get_time(), msg.result.status, msg.result.message)),
            queue_size=10)
        rospy.Service(names.INSPECTION_MARK_SERVICE, InspectionMark, self._on_mark)
        self._publish_findings()
        rospy.loginfo('inspection: run %s (%d findings so far)', self.folder, len(self.store.findings))

    def _locked(self, callback):
        def locked(msg):
            with self._lock:
                callback(msg)
        return locked

    def _use_map(self, name, points):
        try:
            pipe_map = network.load(network.world_path(name))
        except network.WorldError as error:
            rospy.logerr('inspection: %s', error)
            return
        first = [p for p in points if p in pipe_map.points][:1]
        launch = LAUNCH_PIT if LAUNCH_PIT in pipe_map.points else (first[0] if first else None)
        launch_m = pipe_map.points[launch] if launch else pipe_map.start_m
        with self._lock:
            self.recorder.set_map(pipe_map, launch_m)
        about = {'run': os.path.basename(self.folder), 'map': name, 'launch_pit_mm': launch_m * 1000}
        before = store.read_about(self.folder)
        if before.get('map') not in (None, name) and self.store.findings:
            rospy.logwarn('inspection: the run %s holds findings on map %s and goes on with map %s: its report draws '
                          'them on %s (start a new run for another map: new_run:=true)',
                          self.folder, before['map'], name, name)
        if before != about:
            store.write_about(self.folder, about)
        rospy.loginfo('inspection: map %s, launch pit at %.0f mm', name, launch_m * 1000)

    def _on_mission(self, msg):
        with self._lock:        # into the timeline before the map loads, ahead of the mission's first feedback
            self.recorder.mission_goal(msg.header.stamp.to_sec(), msg.goal.map, list(msg.goal.points),
                                       msg.goal_id.id)
        self._use_map(msg.goal.map, list(msg.goal.points))

    def _on_state(self, msg):
        if not msg.stale:
            with self._lock:
                self.recorder.robot_state(msg.name, msg.position, msg.orientation, msg.odometry)

    def _on_mark(self, req):
        stamp_s = rospy.get_time()
        try:
            with self._lock:
                where = self.recorder.where()          # where the robot is when marked, before the frames come
            frames = _next_frames()
            with self._lock:
                self.recorder.forget_frames()
                for camera, frame in frames.items():
                    self.recorder.frame(camera, frame)
                finding = self.recorder.mark(req.kind, req.note, stamp_s, _caller(req), where=where)
        except (fd.FindingError, store.RunError, OSError) as refused:
            rospy.logwarn('inspection: finding not recorded: %s', refused)
            return InspectionMarkResponse(ok=False, message='not recorded: %s' % refused, number=0)
        self._publish_findings()
        pos = finding['position']
        message = 'finding %d (%s): %.0f mm from the launch pit (+/- %.0f mm), %s' % (
            finding['number'], finding['kind'], pos['from_launch_pit_mm'], pos['uncertainty_mm'], pos['clock_text'])
        rospy.loginfo('inspection: %s', message)
        return InspectionMarkResponse(ok=True, message=message, number=finding['number'])

    def _publish_findings(self):
        self._findings_pub.publish(String(data=json.dumps(
            {'run': self.folder, 'findings': self.store.findings}, sort_keys=True)))


def _next_frames():
    """{camera: :data:`rec.Frame`} of the next image of each camera that
    sends one within :data:`FRAME_WAIT_S` (the cameras asked at once)."""
    frames = {}

    def grab(camera):
        try:
            msg = rospy.wait_for_message(names.CAMERA_NAMESPACES[camera] + '/image_raw', Image, FRAME_WAIT_S)
        except rospy.ROSException:
            return
        frames[camera] = rec.Frame(msg.width, msg.height, msg.encoding, msg.step, msg.data,
                                   msg.header.stamp.to_sec())
    threads = [threading.Thread(target=grab, args=(camera,)) for camera in rec.CAMERAS]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return frames


def _caller(req):
    """The node that called the service (the panel's is the manager), for the finding's ``source``."""
    return getattr(req, '_connection_header', {}).get('callerid', 'unknown')


def _progress(feedback):
    """The recorder's mission_feedback arguments after the time, from a MissionFeedback."""
    return (feedback.step, feedback.steps, feedback.pab, feedback.option, feedback.along_mm, feedback.state,
            feedback.waiting_for)


def main():
    rospy.init_node('inspection')
    try:
        InspectionNode()
    except (store.RunError, OSError) as error:
        rospy.logfatal('inspection: cannot go on with the run: %s (start a new run: new_run:=true)', error)
        raise SystemExit(1)
    rospy.spin()
