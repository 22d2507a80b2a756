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
      last_byte_ms_(0), last_rx_ms_(0), last_sync_ms_(0), negotiating_(false),
      configured_(false) {
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
    negotiate(now);
  } else if (topic_ == ROS_ID_TIME) {
    if (negotiating_ && len_ == 8) {
      negotiating_ = false;
      configured_ = true;
      handler_->on_configured(now);
    }
  } else if (topic_ == ROS_ID_TX_STOP) {
    unconfigure(now);
  } else if (configured_ && is_subscribed(topic_)) {
    handler_->on_message(topic_, in_, len_, now);
  } else {
    ++counters.unknown_topic;
  }
}

void RosserialDevice::negotiate(uint32_t now) {
  unconfigure(now);
  for (uint8_t i = 0; i < TOPIC_COUNT; ++i) {
    const TopicDef &t = kTopics[i];
    Writer w = {out_, ROS_OUT_BUF, 0, true};
    w.u16(t.id);
    w.str(t.name);
    w.str(t.type);
    w.str(t.md5);
    w.u32(ROS_IN_BUF);
    if (w.ok) send(t.subscriber ? ROS_ID_SUBSCRIBER : ROS_ID_PUBLISHER, out_, w.pos);
  }
  negotiating_ = true;
  request_time(now);
}

void RosserialDevice::unconfigure(uint32_t now) {
  bool was = configured_;
  configured_ = false;
  negotiating_ = false;
  if (was) handler_->on_unconfigured(now);
}

void RosserialDevice::request_time(uint32_t now) {
  last_sync_ms_ = now;
  send(ROS_ID_TIME, 0, 0);
}

void RosserialDevice::poll(uint32_t now) {
  if (!configured_ && !negotiating_) return;
  if ((uint32_t)(now - last_rx_ms_) > ROS_LINK_TIMEOUT_MS) {
    unconfigure(now);
    return;
  }
  if ((uint32_t)(now - last_sync_ms_) >= ROS_SYNC_PERIOD_MS) request_time(now);
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
