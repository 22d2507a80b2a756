// The device side of the rosserial protocol (Noetic, version byte 0xFE),
// written for this bridge: four fixed topics, no dynamic allocation.
//
// Handshake: the host sends a topic request (topic 0, empty); we answer with
// one TopicInfo per topic and a time request (topic 10, empty); the host's
// time reply completes the handshake ("configured"). Every SYNC_PERIOD_MS we
// ask for the time again; no valid frame from the host for LINK_TIMEOUT_MS,
// a TX_STOP, a new topic request, or the bridge's watchdog drops the
// configuration. Unconfigured, we publish nothing and ignore every command.
#ifndef PIRATE_ROSSERIAL_DEVICE_H
#define PIRATE_ROSSERIAL_DEVICE_H

#include <stdint.h>

#define ROS_IN_BUF 64        // largest incoming payload (SetpointArray: 26)
#define ROS_OUT_BUF 112      // largest outgoing payload (a TopicInfo: 96)
#define ROS_BYTE_TIMEOUT_MS 20
#define ROS_SYNC_PERIOD_MS 1000
#define ROS_LINK_TIMEOUT_MS 3000

#define ROS_ID_PUBLISHER 0
#define ROS_ID_SUBSCRIBER 1
#define ROS_ID_TIME 10
#define ROS_ID_TX_STOP 11

class RosHandler {
 public:
  // A checked frame on one of our subscribed topics, while configured.
  virtual void on_message(uint16_t topic, const uint8_t *payload, uint16_t len,
                          uint32_t now) = 0;
  virtual void on_configured(uint32_t now) = 0;   // handshake completed
  virtual void on_unconfigured(uint32_t now) = 0; // link lost / tx stop / renegotiation
};

struct RosCounters {
  uint16_t frames_in, frames_out, checksum_errors, oversize, timeouts, unknown_topic;
};

class RosserialDevice {
 public:
  explicit RosserialDevice(RosHandler *handler);
  void feed(uint8_t byte, uint32_t now);
  void poll(uint32_t now);
  bool configured() const { return configured_; }
  // Forget the handshake (the bridge's watchdog tripped): stop publishing
  // and ignore commands until the host negotiates again. Our host notices
  // the silence and renegotiates within its sync timeout.
  void drop_configuration(uint32_t now) { unconfigure(now); }
  // Send one frame; false if not configured or the payload does not fit.
  bool publish(uint16_t topic, const uint8_t *payload, uint16_t len);
  RosCounters counters;

 private:
  enum State { SYNC, VERSION, LEN_L, LEN_H, LEN_CHK, TOPIC_L, TOPIC_H, DATA, CHK };
  void reset_parser() { state_ = SYNC; }
  void handle_frame(uint32_t now);
  void negotiate(uint32_t now);
  void unconfigure(uint32_t now);
  void send(uint16_t topic, const uint8_t *payload, uint16_t len);
  void request_time(uint32_t now);

  RosHandler *handler_;
  State state_;
  uint16_t len_, index_, topic_;
  uint8_t sum_;
  uint8_t in_[ROS_IN_BUF];
  uint8_t out_[ROS_OUT_BUF];
  uint32_t last_byte_ms_, last_rx_ms_, last_sync_ms_;
  bool negotiating_, configured_;
};

#endif
