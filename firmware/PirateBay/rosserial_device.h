// The device side of the rosserial protocol (Noetic, version byte 0xFE),
// written for this bridge: four fixed topics, no dynamic allocation.
//
// Handshake: we announce our topics (one TopicInfo each) and ask for the
// time (topic 10, an 8-byte std_msgs/Time as ros_lib sends); the host's time
// reply completes it ("configured"). We announce when the host asks (topic
// request, topic 0) and, while unconfigured, on our own every
// ROS_ANNOUNCE_PERIOD_MS: after a reset or a lost link the device brings
// the link back itself, so a host that only renegotiates after its own long
// timeout (rosserial_python: 15 s) still recovers within a second.
//
// Freshness gate (why stale bytes are never applied): the link is FIFO and
// a host answers each time request once. When the gate closes (a watchdog
// trip, an announcement) we note how many of our time requests are still
// unanswered (U) and send one more; the (U+1)-th reply after that can only
// answer a request sent after the gate closed, so every byte after it was
// written by the host after the gate closed. Until then commands are
// "stale" (the handler decides what that means), and each reply is
// followed at once by the next request, so waiting for U+1 replies costs
// U+1 round trips. A request still unanswered after ROS_REQUEST_LOST_MS
// counts as lost (the one assumption: the link never holds a device frame
// that long; a USB-serial chip drops what the host does not read); a
// request counted in flight that was in fact lost only makes U larger than
// the truth: one more reply to wait for, never less safe.
//
// No valid frame from the host for ROS_LINK_TIMEOUT_MS, or a TX_STOP,
// drops the configuration: we then publish nothing but announcements.
#ifndef PIRATE_ROSSERIAL_DEVICE_H
#define PIRATE_ROSSERIAL_DEVICE_H

#include <stdint.h>

#define ROS_IN_BUF 64        // largest incoming payload (SetpointArray: 26)
#define ROS_OUT_BUF 112      // largest outgoing payload (a TopicInfo: 96)
#define ROS_BYTE_TIMEOUT_MS 20
#define ROS_SYNC_PERIOD_MS 1000      // time request while configured (host liveness)
#define ROS_GATE_PERIOD_MS 250       // time request while the freshness gate is closed
#define ROS_ANNOUNCE_PERIOD_MS 500   // unsolicited announcement while unconfigured
#define ROS_LINK_TIMEOUT_MS 3000
#define ROS_REQUEST_LOST_MS 3000
#define ROS_IN_FLIGHT_MAX 32         // time requests remembered; none sent beyond

#define ROS_ID_PUBLISHER 0
#define ROS_ID_SUBSCRIBER 1
#define ROS_ID_LOG 7
#define ROS_ID_TIME 10
#define ROS_ID_TX_STOP 11

// rosserial_msgs/Log levels.
#define ROS_LOG_INFO 1
#define ROS_LOG_WARN 2

class RosHandler {
 public:
  // A checked frame on one of our subscribed topics; `fresh` is false while
  // the freshness gate is closed or the link is not configured.
  virtual void on_message(uint16_t topic, const uint8_t *payload, uint16_t len,
                          bool fresh, uint32_t now) = 0;
  virtual void on_configured(uint32_t now) = 0;   // handshake completed
  virtual void on_unconfigured(uint32_t now) = 0; // link lost / tx stop
};

struct RosCounters {
  uint16_t frames_in, frames_out, checksum_errors, oversize, timeouts, unknown_topic,
      announcements, stale;
};

class RosserialDevice {
 public:
  explicit RosserialDevice(RosHandler *handler);
  void feed(uint8_t byte, uint32_t now);
  void poll(uint32_t now);
  bool configured() const { return configured_; }
  bool fresh() const { return configured_ && gate_ == 0; }
  // Close the freshness gate (the bridge's watchdog tripped): the link stays
  // up, commands count as stale until the host answers a new time request.
  void close_gate(uint32_t now);
  // Send one frame; false if not configured or the payload does not fit.
  bool publish(uint16_t topic, const uint8_t *payload, uint16_t len);
  // rosserial_msgs/Log at `level` (forwarded by the host to rosout).
  bool log(uint8_t level, const char *text);
  RosCounters counters;

 private:
  enum State { SYNC, VERSION, LEN_L, LEN_H, LEN_CHK, TOPIC_L, TOPIC_H, DATA, CHK };
  void handle_frame(uint32_t now);
  void on_time_reply(uint32_t now);
  void announce(uint32_t now);
  void unconfigure(uint32_t now);
  void send(uint16_t topic, const uint8_t *payload, uint16_t len);
  void request_time(uint32_t now);

  RosHandler *handler_;
  State state_;
  uint16_t len_, index_, topic_;
  uint8_t sum_;
  uint8_t in_[ROS_IN_BUF];
  uint8_t out_[ROS_OUT_BUF];
  uint32_t last_byte_ms_, last_rx_ms_, last_sync_ms_, last_announce_ms_;
  void forget_lost_requests(uint32_t now);
  uint32_t in_flight_[ROS_IN_FLIGHT_MAX];  // send times of unanswered time requests, oldest first
  uint8_t in_flight_count_, gate_;
  bool negotiating_, configured_;
};

#endif
