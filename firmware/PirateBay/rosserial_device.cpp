#include "rosserial_device.h"

#include <string.h>

#include "hal.h"
#include "pirate_generated.h"

namespace {

struct TopicDef {
  uint16_t id;
  const char *name, *type, *md5;
  uint8_t subscriber;
};

#define TOPIC_DEF(X) {TOPIC_##X##_ID, TOPIC_##X##_NAME, TOPIC_##X##_TYPE, TOPIC_##X##_MD5, TOPIC_##X##_SUBSCRIBER}
const TopicDef kTopics[TOPIC_COUNT] = {TOPIC_DEF(SMALL_STATE), TOPIC_DEF(SETPOINT),
                                       TOPIC_DEF(CONTROL), TOPIC_DEF(LIMITS)};

// Bounds-checked little-endian writer into a fixed buffer.
struct Writer {
  uint8_t *buf;
  uint16_t cap, pos;
  bool ok;
  void byte(uint8_t b) {
    if (pos < cap) buf[pos++] = b; else ok = false;
  }
  void u16(uint16_t v) { byte(v & 0xFF); byte(v >> 8); }
  void u32(uint32_t v) { u16(v & 0xFFFF); u16(v >> 16); }
  void str(const char *s) {
    uint16_t n = (uint16_t)strlen(s);
    u32(n);
    for (uint16_t i = 0; i < n; ++i) byte((uint8_t)s[i]);
  }
};

bool is_subscribed(uint16_t topic) {
  for (uint8_t i = 0; i < TOPIC_COUNT; ++i)
    if (kTopics[i].id == topic && kTopics[i].subscriber) return true;
  return false;
}

}  // namespace

RosserialDevice::RosserialDevice(RosHandler *handler)
    : handler_(handler), state_(SYNC), len_(0), index_(0), topic_(0), sum_(0),
      last_byte_ms_(0), last_rx_ms_(0), last_sync_ms_(0),
      last_announce_ms_(0u - ROS_ANNOUNCE_PERIOD_MS), in_flight_count_(0), gate_(1),
      negotiating_(false), configured_(false) {
  memset(&counters, 0, sizeof counters);
}

void RosserialDevice::feed(uint8_t b, uint32_t now) {
  if (state_ != SYNC && (uint32_t)(now - last_byte_ms_) > ROS_BYTE_TIMEOUT_MS) {
    ++counters.timeouts;  // a frame cut short: never let it swallow the next one
    state_ = SYNC;
  }
  last_byte_ms_ = now;
  switch (state_) {
    case SYNC:
      if (b == 0xFF) state_ = VERSION;
      break;
    case VERSION:
      state_ = (b == 0xFE) ? LEN_L : (b == 0xFF ? VERSION : SYNC);
      break;
    case LEN_L:
      len_ = b;
      state_ = LEN_H;
      break;
    case LEN_H:
      len_ |= (uint16_t)b << 8;
      state_ = LEN_CHK;
      break;
    case LEN_CHK:
      if ((uint8_t)((len_ & 0xFF) + (len_ >> 8) + b) != 0xFF) {
        ++counters.checksum_errors;
        state_ = SYNC;
      } else if (len_ > ROS_IN_BUF) {
        ++counters.oversize;
        state_ = SYNC;
      } else {
        state_ = TOPIC_L;
      }
      break;
    case TOPIC_L:
      topic_ = b;
      sum_ = b;
      state_ = TOPIC_H;
      break;
    case TOPIC_H:
      topic_ |= (uint16_t)b << 8;
      sum_ += b;
      index_ = 0;
      state_ = len_ ? DATA : CHK;
      break;
    case DATA:
      if (index_ < ROS_IN_BUF) in_[index_] = b;  // len_ <= ROS_IN_BUF checked above
      ++index_;
      sum_ += b;
      if (index_ >= len_) state_ = CHK;
      break;
    case CHK:
      state_ = SYNC;
      if ((uint8_t)(sum_ + b) != 0xFF) {
        ++counters.checksum_errors;
      } else {
        ++counters.frames_in;
        handle_frame(now);
      }
      break;
  }
}

void RosserialDevice::handle_frame(uint32_t now) {
  last_rx_ms_ = now;
  if (topic_ == ROS_ID_PUBLISHER && len_ == 0) {
    unconfigure(now);  // the host (re)started: a new session
    announce(now);
  } else if (topic_ == ROS_ID_TIME) {
    if (len_ == 8) on_time_reply(now);
  } else if (topic_ == ROS_ID_TX_STOP) {
    unconfigure(now);
  } else if (is_subscribed(topic_)) {
    bool fresh_now = fresh();
    if (!fresh_now) ++counters.stale;
    handler_->on_message(topic_, in_, len_, fresh_now, now);
  } else {
    ++counters.unknown_topic;
  }
}

void RosserialDevice::on_time_reply(uint32_t now) {
  last_announce_ms_ = now;  // the host is answering: no need to announce again yet
  if (in_flight_count_) {  // FIFO: the reply answers the oldest request in flight
    --in_flight_count_;
    memmove(in_flight_, in_flight_ + 1, in_flight_count_ * sizeof in_flight_[0]);
  }
  if (!gate_) return;
  if (--gate_) {
    request_time(now);  // ping-pong: the next reply we need is one round trip away
    return;
  }
  if (negotiating_) {
    negotiating_ = false;
    configured_ = true;
    handler_->on_configured(now);
  }
}

void RosserialDevice::announce(uint32_t now) {
  last_announce_ms_ = now;
  ++counters.announcements;
  for (uint8_t i = 0; i < TOPIC_COUNT; ++i) {
    const TopicDef &t = kTopics[i];
    Writer w = {out_, ROS_OUT_BUF, 0, true};
    w.u16(t.id);
    w.str(t.name);
    w.str(t.type);
    w.str(t.md5);
    w.u32(t.subscriber ? ROS_IN_BUF : ROS_OUT_BUF);  // as ros_lib: the buffer for that direction
    if (w.ok) send(t.subscriber ? ROS_ID_SUBSCRIBER : ROS_ID_PUBLISHER, out_, w.pos);
  }
  negotiating_ = true;
  close_gate(now);
}

void RosserialDevice::close_gate(uint32_t now) {
  forget_lost_requests(now);
  gate_ = in_flight_count_ + 1;
  request_time(now);
}

void RosserialDevice::unconfigure(uint32_t now) {
  bool was = configured_;
  configured_ = false;
  negotiating_ = false;
  if (was) handler_->on_unconfigured(now);
}

void RosserialDevice::forget_lost_requests(uint32_t now) {
  uint8_t lost = 0;
  while (lost < in_flight_count_ && (uint32_t)(now - in_flight_[lost]) > ROS_REQUEST_LOST_MS) ++lost;
  if (!lost) return;
  in_flight_count_ -= lost;
  memmove(in_flight_, in_flight_ + lost, in_flight_count_ * sizeof in_flight_[0]);
}

void RosserialDevice::request_time(uint32_t now) {
  last_sync_ms_ = now;
  forget_lost_requests(now);
  if (in_flight_count_ >= ROS_IN_FLIGHT_MAX) return;  // never lose count of one in flight
  in_flight_[in_flight_count_++] = now;
  const uint8_t zero_time[8] = {0, 0, 0, 0, 0, 0, 0, 0};  // std_msgs/Time, as ros_lib sends
  send(ROS_ID_TIME, zero_time, sizeof zero_time);
}

void RosserialDevice::poll(uint32_t now) {
  if (!configured_) {
    if ((uint32_t)(now - last_announce_ms_) >= ROS_ANNOUNCE_PERIOD_MS) announce(now);
    return;
  }
  if ((uint32_t)(now - last_rx_ms_) > ROS_LINK_TIMEOUT_MS) {
    unconfigure(now);
    return;
  }
  uint32_t period = gate_ ? ROS_GATE_PERIOD_MS : ROS_SYNC_PERIOD_MS;
  if ((uint32_t)(now - last_sync_ms_) >= period) request_time(now);
}

bool RosserialDevice::log(uint8_t level, const char *text) {
  Writer w = {out_, ROS_OUT_BUF, 0, true};
  w.byte(level);
  w.str(text);
  if (!w.ok || !configured_) return false;
  send(ROS_ID_LOG, out_, w.pos);
  return true;
}

bool RosserialDevice::publish(uint16_t topic, const uint8_t *payload, uint16_t len) {
  if (!configured_ || len > ROS_OUT_BUF) return false;
  send(topic, payload, len);
  return true;
}

void RosserialDevice::send(uint16_t topic, const uint8_t *payload, uint16_t len) {
  uint8_t head[7] = {0xFF, 0xFE, (uint8_t)(len & 0xFF), (uint8_t)(len >> 8), 0,
                     (uint8_t)(topic & 0xFF), (uint8_t)(topic >> 8)};
  head[4] = (uint8_t)(0xFF - (uint8_t)(head[2] + head[3]));
  uint8_t sum = head[5] + head[6];
  for (uint16_t i = 0; i < len; ++i) sum += payload[i];
  uint8_t chk = (uint8_t)(0xFF - sum);
  hal::link_write(head, sizeof head);
  if (len) hal::link_write(payload, len);
  hal::link_write(&chk, 1);
  ++counters.frames_out;
}
