"""Topic, service and action names, chosen once (doc/interfaces.md).

The array and state topics are those of the report and the author's code
(SPEC 3, Fig 5.1): a Mega flashed for the original system subscribes to
exactly these. Remap in launch files rather than renaming here.
"""
SETPOINT_TOPIC = '/pirate/setpoint_array'     # pirate/SetpointArray
CONTROL_TOPIC = '/pirate/control_array'       # pirate/ControlArray
LIMITS_TOPIC = '/pirate/limits_array'         # pirate/LimitArray
SMALL_STATE_TOPIC = '/pirate/Small_State'     # pirate/SmallState, one per board
#: std_msgs/Empty from serial_node whenever the device announces itself: the
#: link up, or announced again while up (a reset device, a re-handshake).
DEVICE_ANNOUNCED_TOPIC = '/pirate/link/device_announced'
ROBOT_STATE_TOPIC = '/pirate/state'           # pirate/RobotState, SI units
JOINT_STATES_TOPIC = '/joint_states'          # sensor_msgs/JointState (RViz)
IMU_TOPIC = '/pirate/imu'                     # sensor_msgs/Imu, rear-part roll
MIDI_INPUT_TOPIC = '/ram/input/midi'          # pirate/MidiInput
MIDI_OUTPUT_TOPIC = '/ram/input/midiout'      # pirate/MidiOutput
PANEL_DEVICE_TOPIC = '/ram/input/midi_device'  # std_msgs/Bool, latched: the MIDI driver has its panel
OPERATOR_TOPIC = '/pirate/operator'           # std_msgs/String, the panel's messages
JOINT_SENSORS_SERVICE = '/pirate/joint_sensors'   # pirate/JointSensors
IMU_SENSOR_SERVICE = '/pirate/imu_sensor'         # pirate/ImuSensor
SERVER_STATUS_SERVICE = '/pirate/server_status'   # pirate/ServerStatus
PIRATE_ACTION = '/pirate'                     # pirate/PirateAction
#: The physics twin's ground truth (geometry_msgs/PoseArray, one pose per
#: module, pirate.sim.twin_robot.TRUTH_BODIES order): tests, bench, RViz
#: and the mission plot only, never a PAB (the real robot has no such topic).
GROUND_TRUTH_TOPIC = '/pirate/sim/ground_truth'
#: The cameras (sensor_msgs/Image + CameraInfo, image_transport layout:
#: <ns>/image_raw, <ns>/camera_info), twin or real robot alike, and the
#: optical frames (z out of the lens, x right, y down) they are stamped in.
CAMERA_NAMESPACES = {'front': '/pirate/front_camera', 'rear': '/pirate/rear_camera'}
CAMERA_FRAMES = {'front': 'front_camera_optical', 'rear': 'rear_camera_optical'}
CAMERA_POINT_SERVICE = '/pirate/camera/point'  # pirate/CameraPoint: pan and tilt the front camera
#: The manager took in the robot state stamped so (std_msgs/Time), published
#: in simulated time only: the simulator steps on when it hears it
#: (pirate.sim.lockstep, doc/clock.md).
LOCKSTEP_TOPIC = '/pirate/sim/lockstep'
MISSION_ACTION = '/pirate/mission'            # pirate/MissionAction (Supervisory layer)
MISSION_COMMAND_SERVICE = '/pirate/mission/command'   # pirate/MissionCommand: pause, resume, ...
MISSION_POSE_TOPIC = '/pirate/mission/pose'   # geometry_msgs/PoseStamped, estimate on the map
MISSION_ALONG_TOPIC = '/pirate/mission/along_mm'      # std_msgs/Float64, estimate along the path
#: pirate/MissionActionGoal, latched: the mission accepted last, its map and points (a resumed one's too)
MISSION_CURRENT_TOPIC = '/pirate/mission/current'
MISSION_MARKERS_TOPIC = '/pirate/mission/markers'     # visualization_msgs/MarkerArray: route, points, estimate
MISSION_UNCERTAINTY_TOPIC = '/pirate/mission/uncertainty_mm'   # std_msgs/Float64, how far the estimate may be off
INSPECTION_MARK_SERVICE = '/pirate/inspection/mark'    # pirate/InspectionMark: record a finding
INSPECTION_FINDINGS_TOPIC = '/pirate/inspection/findings'   # std_msgs/String, latched: the run's findings (JSON)
MAP_FRAME = 'world'                           # the pipe map's / twin world's frame (world file origin)
