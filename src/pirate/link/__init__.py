"""The rosserial wire protocol (Noetic, protocol version 0xFE), host side.

Split so each part can be tested alone (STYLE "Serial protocols"):

- :mod:`.protocol`  frame encode/decode and the incremental stream parser;
- :mod:`.messages`  the protocol's own payloads (TopicInfo, Time, Log);
- :mod:`.session`   the host's negotiation/time-sync state machine;
- :mod:`.outbox`    latest-value-per-topic store with a maximum age;
- :mod:`.host`      port I/O, threads and ROS (the only module importing rospy).

Nothing in this package except :mod:`.host` imports rospy or opens a port.
"""
