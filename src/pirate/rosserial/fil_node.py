"""ROS wrapper of firmware-in-the-loop (nodes/fil_robot).

Starts the native firmware between a pseudo-terminal at ``~link`` (the
port serial_node opens) and simulated PICO boards around a PirateModel.
Private params: ``~link`` (path of the pty symlink), ``~baud`` (paced line
rate, 57600), ``~pipe_diameter`` (mm), ``~orientation`` (rad),
``~seed`` (sensor noise, -1 none), ``~firmware`` (path of
pirate_bay_native; empty: build it with firmware/Makefile).
FIL runs in wall time (the firmware has its own clock): no /clock.
"""
import rospy
import rospkg

from pirate.rosserial.fil import FirmwareInTheLoop, build_native_firmware
from pirate.sim.model import PirateModel


def main():
    rospy.init_node('fil_robot')
    firmware = rospy.get_param('~firmware', '')
    if not firmware:
        try:
            firmware = build_native_firmware(rospkg.RosPack().get_path('pirate'))
        except RuntimeError as error:
            rospy.logfatal(str(error))
            raise SystemExit(1)
    seed = int(rospy.get_param('~seed', -1))
    model = PirateModel(pipe_diameter=rospy.get_param('~pipe_diameter', 90),
                        orientation=float(rospy.get_param('~orientation', 1.5707963)),
                        seed=seed if seed >= 0 else None)
    fil = FirmwareInTheLoop(firmware, model, rospy.get_param('~link'),
                            baud=int(rospy.get_param('~baud', 57600)), record=False)
    fil.start()
    rospy.on_shutdown(fil.stop)
    rospy.loginfo('firmware in the loop: %s on %s', firmware, fil.link_path)
    rospy.spin()
