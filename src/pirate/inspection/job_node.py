"""``rosrun pirate inspection_job [JOB.yaml]``: an inspection job over ROS.

Runs the job's route as a mission (pirate.supervisory.route_client_ros:
planned here first, then run by the mission executive, its progress
printed), marks each of the job's findings through
``/pirate/inspection/mark`` when the mission's estimate
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
import sys
import threading

import rospy
from std_msgs.msg import Float64

from pirate import names, paths
from pirate.inspection import job as jobs
from pirate.inspection import report, store
from pirate.msg import MissionActionFeedback
from pirate.srv import InspectionMark
from pirate.supervisory import route_client_ros
from pirate.supervisory.plan_cli import load_settings
from pirate.world import network

DEFAULT_JOB = os.path.join(paths.CONFIG_DIR, 'jobs', 'inspection_demo.yaml')
MARK_SERVICE_WAIT_S = 30.0


class Marker(object):
    """Marks the job's findings as the mission's estimate passes them; prints each."""

    def __init__(self, due, out):
        self._due = due
        self._out = out
        self.failed = []
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
                self._record(mark, msg.data)

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
    marker = Marker(jobs.due_marks(job.marks, pipe_map, load_settings()[0]['robot']), out)
    route = argparse.Namespace(route=[job.map] + job.points, speed=0.0, level='full', check=False, no_home=False)
    status = route_client_ros.run_route(route, out)
    for mark in marker.left():
        out('not marked: %s at %.0f mm on the way %s (the estimate never passed it)'
            % (mark.kind, mark.along_mm, mark.leg))
    written = write_report()
    ok = status == 0 and not marker.failed and not marker.left() and written
    out('inspection job %s' % ('done' if ok else 'FAILED'))
    return 0 if ok else 1
