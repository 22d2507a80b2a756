#!/usr/bin/env python3
"""serial_node with a scripted rosserial device: the features a ros_lib
device may use, live over a pty.

The device here is this test speaking the protocol (pirate.link codec) on
a pseudo-terminal, in the shapes recorded from a real ros_lib device
(test/data/rosserial): it announces a publisher, a subscriber with a 32-byte
buffer, a ServiceServer (pirate/ServerStatus) and a ServiceClient
(pirate/ImuSensor), then: a parameter request, a call of the laptop's
service, answers a ROS call of its own service, a WARN log, and a frame of
another protocol version. Checked on ROS: each answer, the log at WARN
without prefix, an oversize message refused, /diagnostics ERROR.
"""
import io
import os
import pty
import sys
import threading
import tty
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rosgraph_msgs.msg import Log
from std_msgs.msg import String

import fil_harness
from fil_harness import wait_for
from pirate.link import messages, protocol
from pirate.srv import ImuSensor, ImuSensorResponse, ServerStatus, ServerStatusResponse

PUB, SUB, SRV_RES, SRV_REQ, CLI_REQ, CLI_RES = 100, 101, 102, 103, 104, 105


def serialise(msg):
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


class ScriptedDevice(object):
    """The device end of a pty: announces itself when asked, answers time
    requests' replies by doing nothing, records every frame from the host."""

    def __init__(self):
        self.master, slave = pty.openpty()
        tty.setraw(slave)
        self.path = os.ttyname(slave)
        self._slave = slave            # kept open: the pty lives until close()
        self.frames = []               # (topic, payload) from the host
        self.parser = protocol.FrameParser()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run)
        self._thread.daemon = True
        self._thread.start()

    def send(self, topic, payload=b''):
        os.write(self.master, protocol.encode(topic, payload))

    def _announce(self):
        def info(kind, topic_id, name, type_name, md5, size=512):
            self.send(kind, messages.encode_topic_info(
                messages.TopicInfo(topic_id, name, type_name, md5, size)))
        info(protocol.ID_PUBLISHER, PUB, '/device/out', String._type, String._md5sum)
        info(protocol.ID_SUBSCRIBER, SUB, '/device/in', String._type, String._md5sum, size=32)
        # a service's halves: the service type, each half's md5 (as ros_lib announces)
        info(2, SRV_RES, '/device/status', ServerStatus._type,
             ServerStatus._response_class._md5sum)
        info(3, SRV_REQ, '/device/status', ServerStatus._type,
             ServerStatus._request_class._md5sum)
        info(4, CLI_REQ, '/laptop/imu', ImuSensor._type, ImuSensor._request_class._md5sum)
        info(5, CLI_RES, '/laptop/imu', ImuSensor._type, ImuSensor._response_class._md5sum)
        self.send(protocol.ID_TIME, bytes(8))

    def _run(self):
        while not self._stop.is_set():
            try:
                data = os.read(self.master, 4096)
            except OSError:
                return
            for frame in self.parser.feed(data):
                self.frames.append((frame.topic, frame.payload))
                if frame.topic == protocol.ID_PUBLISHER:
                    self._announce()
                elif frame.topic == SRV_REQ:   # a ROS call of our ServiceServer
                    self.send(SRV_RES, serialise(ServerStatusResponse(
                        server_state='Idle Clamped', robot_connected=True)))

    def received(self, topic):
        return [p for t, p in list(self.frames) if t == topic]

    def close(self):
        self._stop.set()
        os.close(self._slave)
        os.close(self.master)


class DeviceFeaturesTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.rosout, cls.diagnostics = [], []
        rospy.Subscriber('/rosout', Log, cls.rosout.append, queue_size=100)
        rospy.Subscriber('/diagnostics', DiagnosticArray, cls.diagnostics.append, queue_size=20)
        rospy.Service('/laptop/imu', ImuSensor, lambda req: ImuSensorResponse(roll=1.5))
        cls.device = ScriptedDevice()
        rospy.set_param('/serial_node_%d/gain' % os.getpid(), 7)
        _, serial_node = fil_harness.build()
        cls.host = fil_harness.spawn_serial_node(serial_node, cls.device.path)
        wait_for(lambda: cls.device.received(protocol.ID_TIME), 30.0, 'the time reply')
        rospy.wait_for_service('/device/status', 20.0)

    @classmethod
    def tearDownClass(cls):
        fil_harness.stop_process(cls.host)
        cls.device.close()

    def test_parameter_served(self):
        self.device.send(protocol.ID_PARAMETER_REQUEST, struct_string('~gain'))
        wait_for(lambda: self.device.received(protocol.ID_PARAMETER_REQUEST), 10.0, 'param')
        self.assertEqual(self.device.received(protocol.ID_PARAMETER_REQUEST)[0],
                         messages.encode_param_response(ints=[7]))

    def test_ros_call_of_the_device_service(self):
        response = rospy.ServiceProxy('/device/status', ServerStatus)()
        self.assertEqual((response.server_state, response.robot_connected),
                         ('Idle Clamped', True))

    def test_device_calls_the_laptop_service(self):
        self.device.send(CLI_REQ, b'')
        wait_for(lambda: self.device.received(CLI_RES), 10.0, 'the laptop service answer')
        answer = ImuSensorResponse()
        answer.deserialize(self.device.received(CLI_RES)[0])
        self.assertEqual(answer.roll, 1.5)

    def test_log_at_its_level_without_prefix(self):
        self.device.send(protocol.ID_LOG, bytes([2]) + struct_string('scripted warn'))
        wait_for(lambda: [m for m in list(self.rosout) if m.msg == 'scripted warn'], 10.0,
                 'the device log on /rosout')
        (log,) = [m for m in list(self.rosout) if m.msg == 'scripted warn']
        self.assertEqual(log.level, Log.WARN)

    def test_message_larger_than_the_device_buffer_refused(self):
        pub = rospy.Publisher('/device/in', String, queue_size=5)
        wait_for(lambda: pub.get_num_connections() > 0, 10.0, 'serial_node subscribing')
        pub.publish(String(data='x' * 40))       # 44 bytes > the 32 announced
        wait_for(lambda: self._diagnostic('oversize_refused') == '1', 10.0, 'the refusal')
        pub.publish(String(data='short'))
        wait_for(lambda: self.device.received(SUB), 10.0, 'the short message')
        self.assertEqual(self.device.received(SUB), [serialise(String(data='short'))])

    def _diagnostic(self, key):
        values = [v.value for a in list(self.diagnostics) for s in a.status
                  if s.name.endswith(': serial link') for v in s.values if v.key == key]
        return values[-1] if values else None

    def test_other_protocol_version_on_diagnostics(self):
        os.write(self.device.master, bytes([0xFF, 0xFD, 0, 0, 0xFF, 0, 0, 0xFF]))
        wait_for(lambda: [s for a in list(self.diagnostics) for s in a.status
                          if s.level == DiagnosticStatus.ERROR
                          and s.message.startswith('Mismatched protocol version')],
                 10.0, 'ERROR on /diagnostics')


def struct_string(text):
    data = text.encode()
    return len(data).to_bytes(4, 'little') + data


if __name__ == '__main__':
    rospy.init_node('fil_device_features_test', anonymous=True)
    rostest.rosrun('pirate', 'fil_device_features', DeviceFeaturesTest, sys.argv)
