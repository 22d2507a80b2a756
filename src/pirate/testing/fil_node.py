"""ROS wrapper of firmware-in-the-loop (nodes/fil_robot).

Starts the native firmware between a pseudo-terminal at ``~link`` (the
port serial_node opens) and simulated PICO boards around the physics twin.
Private params: ``~link`` (path of the pty symlink), ``~baud`` (paced line
rate, 57600), ``~world`` (the twin's pipe network; empty: the straight
pipe of ``~pipe_diameter``), ``~pipe_diameter`` (mm), ``~orientation`` (rad),
``~joints`` (start angles, as sim_robot's), ``~seed`` (sensor noise, -1 none), ``~firmware`` (path of
pirate_bay_native; empty: build it with firmware/Makefile).
FIL runs in wall time (the firmware has its own clock): no /clock.

Faults for tests, on ``~fault`` (std_msgs/String): ``unplug`` (the pty
closes), ``replug`` (a new pty, the Mega resets), ``reset`` (the Mega
resets, cable in), ``stall SECONDS`` (nothing crosses the link), ``mute
BOARD`` / ``unmute`` (a board stops / starts answering on the bus).
Anything else is refused with a logged reason.
"""
import rospy
import rospkg
from std_msgs.msg import String

from pirate.robot import tables
from pirate.sim import robot_end
from pirate.testing.fil import FirmwareInTheLoop, build_native_firmware


def main():
    rospy.init_node('fil_robot')
    firmware = rospy.get_param('~firmware', '')
    if not firmware:
        try:
            firmware = build_native_firmware(rospkg.RosPack().get_path('pirate'))
        except RuntimeError as error:
            rospy.logfatal(str(error))
            raise SystemExit(1)
    model = robot_end.of_node(rospy.get_param, rospy.logfatal)
    fil = FirmwareInTheLoop(firmware, model, rospy.get_param('~link'),
                            baud=int(rospy.get_param('~baud', 57600)), record=False)
    fil.start()
    rospy.on_shutdown(fil.stop)
    rospy.Subscriber('~fault', String, lambda msg: inject(fil, msg.data), queue_size=5)
    rospy.loginfo('firmware in the loop: %s on %s', firmware, fil.link_path)
    rospy.spin()


def inject(fil, text):
    """Carry out one fault command (see module docstring)."""
    words = text.split()
    if words == ['unplug']:
        fil.unplug()
    elif words == ['replug']:
        fil.replug()
    elif words == ['reset']:
        fil.reset()
    elif words == ['unmute']:
        fil.mute(None)
    elif len(words) == 2 and words[0] == 'mute' and words[1] in map(str, tables.BOARDS):
        fil.mute(int(words[1]))
    elif len(words) == 2 and words[0] == 'stall':
        try:
            seconds = float(words[1])
        except ValueError:
            seconds = -1.0
        if not 0 < seconds <= 60:
            rospy.logerr('fil_robot: stall needs 0 < seconds <= 60, got %r', words[1])
            return
        fil.stall(seconds)
    else:
        rospy.logerr('fil_robot: unknown fault %r (unplug | replug | reset | stall SECONDS '
                     '| mute BOARD | unmute)', text)
        return
    rospy.logwarn('fil_robot: fault injected: %s', text)
