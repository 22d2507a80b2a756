"""``rosrun pirate inspection_job [JOB.yaml]``: an inspection job over ROS.

Runs the job's route as a mission (pirate.supervisory.route_client_ros:
planned here first, then run by the mission executive, its progress
printed), marks each of the job's findings through
``/pirate/inspection/mark`` and makes each of its inspection stops
(pausing the mission, turning the camera through ``/pirate/camera/point``,
recording views) when the mission's estimate
(``/pirate/mission/along_mm``) passes it on its leg, in or back (the
mission's feedback: back from its first step taken rear first;
pirate.inspection.job), and at
the end writes the run's inspection report (pirate.inspection.report) and
prints its path. Needs the stack with the mission executive and the
inspection node (``roslaunch pirate demo.launch inspection:=true``; make
demo). Default job: config/jobs/inspection_demo.yaml. Exit 0 when the
mission succeeded, every mark was recorded and the report written.
"""
import argparse
import os
import queue
import sys
import threading

import rospy
from std_msgs.msg import Float64

from pirate import names, paths
from pirate.inspection import findings
from pirate.inspection import job as jobs
from pirate.inspection import report, store
from pirate.msg import MissionActionFeedback, RobotState
from pirate.srv import CameraPoint, InspectionMark, MissionCommand
from pirate.supervisory import route_client_ros
from pirate.supervisory.executive import WAIT_RESUME
from pirate.supervisory.plan_cli import load_settings
from pirate.world import network

DEFAULT_JOB = os.path.join(paths.CONFIG_DIR, 'jobs', 'inspection_demo.yaml')
MARK_SERVICE_WAIT_S = 30.0
#: Wheel speed the robot stands at, mm/s, and robot s it must read so before the views.
REST_MM_S, REST_S = 1.0, 0.5
#: How close the camera must read to a view, rad, and robot s it may take to get there
#: (the pan turns 2 rad/s in the twin: a view is under a second away).
POINTED_RAD, POINT_S = 0.05, 3.0
#: Wall s a stop waits for the robot to pause and stand (a busy machine is slow, not wrong).
STAND_WALL_S = 120.0


class StopRobot(object):
    """What an inspection stop asks of the stack (:func:`pirate.inspection.job.run_stop`), over ROS."""

    def __init__(self):
        self._cond = threading.Condition()
        self._state, self._waiting_for, self._rest_since = None, '', None
        self._command = rospy.ServiceProxy(names.MISSION_COMMAND_SERVICE, MissionCommand)
        self._point = rospy.ServiceProxy(names.CAMERA_POINT_SERVICE, CameraPoint)
        self._mark = rospy.ServiceProxy(names.INSPECTION_MARK_SERVICE, InspectionMark)
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self._on_state, queue_size=10)
        rospy.Subscriber(names.MISSION_ACTION + '/feedback', MissionActionFeedback, self._on_feedback,
                         queue_size=10)

    def _on_state(self, msg):
        with self._cond:
            stamp = msg.header.stamp.to_sec()
            moving = msg.stale or abs(msg.velocity) >= REST_MM_S
            self._rest_since = None if moving else (self._rest_since if self._rest_since is not None else stamp)
            self._state = msg
            self._cond.notify_all()

    def _on_feedback(self, msg):
        with self._cond:
            self._waiting_for = msg.feedback.waiting_for
            self._cond.notify_all()

    @staticmethod
    def _call(proxy, *args, **kwargs):
        try:
            said = proxy(*args, **kwargs)
            return said.ok, said.message
        except (rospy.ServiceException, rospy.ROSException) as error:
            return False, str(error)

    def pause(self):
        return self._call(self._command, 'pause')

    def resume(self):
        return self._call(self._command, 'resume')

    def point(self, pan_rad, tilt_rad):
        return self._call(self._point, pan_rad, tilt_rad)

    def mark(self, note):
        return self._call(self._mark, kind=findings.VIEW, note=note)

    def stands(self):
        """The mission paused and the wheels at rest for REST_S robot s."""
        def resting():
            return (self._waiting_for.startswith(WAIT_RESUME) and self._rest_since is not None
                    and self._state.header.stamp.to_sec() - self._rest_since >= REST_S)
        with self._cond:
            return self._cond.wait_for(resting, STAND_WALL_S)

    def pointed(self, pan_rad, tilt_rad):
        """The camera reads within POINTED_RAD of the view, or POINT_S robot s passed."""
        with self._cond:
            if self._state is None:
                return False
            until = self._state.header.stamp.to_sec() + POINT_S

            def there():
                angles = dict(zip(self._state.name, self._state.position))
                return (abs(angles.get('camera_pan', 0.0) - pan_rad) <= POINTED_RAD
                        and abs(angles.get('camera_tilt', 0.0) - tilt_rad) <= POINTED_RAD)
            self._cond.wait_for(lambda: there() or self._state.header.stamp.to_sec() > until, STAND_WALL_S)
            return there()


class Marker(object):
    """Marks the job's findings as the mission's estimate passes them, and
    makes its inspection stops (in a thread of their own); prints each."""

    def __init__(self, due, out):
        self._due = due
        self._out = out
        self.failed = []
        self._stops = queue.Queue()
        self._robot = StopRobot()
        threading.Thread(target=self._make_stops, name='inspection_stops', daemon=True).start()
        self._mark = rospy.ServiceProxy(names.INSPECTION_MARK_SERVICE, InspectionMark)
        self._lock = threading.Lock()
        rospy.Subscriber(names.MISSION_ACTION + '/feedback', MissionActionFeedback, self._on_step, queue_size=10)
        rospy.Subscriber(names.MISSION_ALONG_TOPIC, Float64, self._on_along, queue_size=10)

    def _on_step(self, msg):
        with self._lock:
            self._due.step(msg.feedback.distance_mm, msg.feedback.pab, msg.feedback.step)

    def _on_along(self, msg):
        with self._lock:
            for mark in self._due.passed(msg.data):
                if isinstance(mark, jobs.Stop):
                    self._out('inspection stop at %.0f mm on the way %s: %s' % (msg.data, mark.leg, mark.note))
                    self._stops.put(mark)
                else:
                    self._record(mark, msg.data)

    def _make_stops(self):
        while True:
            stop = self._stops.get()
            if jobs.run_stop(stop, self._robot, self._out) < len(stop.views):
                self.failed.append(stop)

    def _record(self, mark, along_mm):
        try:
            said = self._mark(kind=mark.kind, note=mark.note)
            ok, message = said.ok, said.message
        except (rospy.ServiceException, rospy.ROSException) as error:
            ok, message = False, str(error)
        self._out('mark %s (%s, at %.0f mm on the way %s): %s'
                  % (mark.kind, mark.note, along_mm, mark.leg, message))
        if not ok:
            self.failed.append(mark)

    def left(self):
        with self._lock:
            return self._due.left()


def write_report():
    """Write the current run's report; its path, or None (the reason printed)."""
    root = os.path.expanduser(rospy.get_param('/inspection/root', store.DEFAULT_ROOT))
    run = store.current_run(root)
    status = report.main([run, '--root', root])
    return None if status else os.path.join(root, run, 'report.html')


def main(argv=None):
    parser = argparse.ArgumentParser(prog='inspection_job', description=__doc__.split('\n')[0])
    parser.add_argument('job', nargs='?', default=DEFAULT_JOB, help='job YAML (default %(default)s)')
    args = parser.parse_args(rospy.myargv(argv or sys.argv)[1:])
    try:
        job = jobs.load(args.job)
        pipe_map = network.load(network.world_path(job.map))
    except (jobs.JobError, network.WorldError) as error:
        print('inspection_job: %s' % error, file=sys.stderr)
        return 2
    out = lambda line: print(line, flush=True)  # noqa: E731
    rospy.init_node('inspection_job', anonymous=True)
    try:
        rospy.wait_for_service(names.INSPECTION_MARK_SERVICE, MARK_SERVICE_WAIT_S)
    except rospy.ROSException:
        print('inspection_job: no inspection node at %s (roslaunch pirate inspection.launch)'
              % names.INSPECTION_MARK_SERVICE, file=sys.stderr)
        return 2
    marker = Marker(jobs.due_marks(job.marks + job.stops, pipe_map, load_settings()[0]['robot']), out)
    route = argparse.Namespace(route=[job.map] + job.points, speed=0.0, level='full', check=False, no_home=False)
    status = route_client_ros.run_route(route, out)
    for mark in marker.left():
        what = ('made', 'stop') if isinstance(mark, jobs.Stop) else ('marked', mark.kind)
        out('not %s: %s at %.0f mm on the way %s (the estimate never passed it)' % (what + (mark.along_mm, mark.leg)))
    written = write_report()
    ok = status == 0 and not marker.failed and not marker.left() and written
    out('inspection job %s' % ('done' if ok else 'FAILED'))
    return 0 if ok else 1
