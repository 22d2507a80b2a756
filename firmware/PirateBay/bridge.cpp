#include "bridge.h"

#include <string.h>

#include "hal.h"

namespace {

const BoardMap kBoards[BOARD_COUNT] = BOARD_MAP_ROWS;

int16_t read_i16(const uint8_t *p) { return (int16_t)(p[0] | ((uint16_t)p[1] << 8)); }

// Array element i, or 0 when the board's motor has no element (NO_ELEMENT)
// or the index is out of range: never read past an array.
int16_t at(const int16_t *array, uint8_t size, int8_t i) {
  return (i >= 0 && (uint8_t)i < size) ? array[i] : 0;
}

int16_t signed_copy(int16_t value, int8_t sign) {
  if (sign >= 0) return value;
  return value == -32768 ? 32767 : (int16_t)-value;
}

}  // namespace

Bridge::Bridge()
    : ros_(0), armed_(false), stop_pending_(true), waiting_(false), control_known_(false),
      limits_known_(false), last_setpoint_ms_(0),
      cycle_start_ms_(0), request_ms_(0), next_row_(BOARD_COUNT), seq_(0) {
  memset(&counters, 0, sizeof counters);
  memset(setpoint_, 0, sizeof setpoint_);
  memset(control_, 0, sizeof control_);
  memset(missed_, 0, sizeof missed_);
  memset(reported_silent_, 0, sizeof reported_silent_);
  for (uint8_t i = 0; i < LIMIT_SIZE; ++i) limit_[i] = NO_LIMIT;
}

void Bridge::disarm() {
  armed_ = false;
  stop_pending_ = true;
}

void Bridge::on_configured(uint32_t) { disarm(); }  // fresh setpoint needed after every handshake

void Bridge::on_unconfigured(uint32_t) { disarm(); }

void Bridge::on_message(uint16_t topic, const uint8_t *payload, uint16_t len, bool fresh,
                        uint32_t now) {
  if (topic == TOPIC_SETPOINT_ID && len == 2 * SETPOINT_SIZE) {
    if (!fresh) {  // buffered before a trip or a handshake: never applied
      ++counters.stale_setpoints;
      return;
    }
    for (uint8_t i = 0; i < SETPOINT_SIZE; ++i) setpoint_[i] = read_i16(payload + 2 * i);
    last_setpoint_ms_ = now;
    armed_ = control_known_ && limits_known_;
    ++counters.setpoints;
  } else if (topic == TOPIC_CONTROL_ID && len == 2 * CONTROL_SIZE) {
    for (uint8_t i = 0; i < CONTROL_SIZE; ++i) {
      int16_t code = read_i16(payload + 2 * i);
      if (code < 0 || code > CONTROL_CODE_MAX) {
        ++counters.rejected;
        return;
      }
    }
    for (uint8_t i = 0; i < CONTROL_SIZE; ++i) control_[i] = read_i16(payload + 2 * i);
    control_known_ = true;
    ++counters.controls;
  } else if (topic == TOPIC_LIMITS_ID && len == 2 * LIMIT_SIZE) {
    for (uint8_t i = 0; i < LIMIT_SIZE; ++i) limit_[i] = (uint16_t)read_i16(payload + 2 * i);
    limits_known_ = true;
    ++counters.limits;
  } else {
    ++counters.rejected;
  }
}

void Bridge::request(uint8_t row, uint32_t now) {
  const BoardMap &b = kBoards[row];
  uint8_t frame[BUS_MAX_FRAME];
  uint8_t n;
  ++seq_;
  if (armed_) {
    int16_t sp1 = at(setpoint_, SETPOINT_SIZE, b.sp1);
    n = bus_encode_set(frame, sizeof frame, b.board, seq_,
                       (uint8_t)at(control_, CONTROL_SIZE, b.mode0),
                       (uint8_t)at(control_, CONTROL_SIZE, b.mode1),
                       at(setpoint_, SETPOINT_SIZE, b.sp0), signed_copy(sp1, b.sign1),
                       (b.limit >= 0 && b.limit < LIMIT_SIZE) ? limit_[b.limit] : NO_LIMIT);
  } else {
    n = bus_encode_stop(frame, sizeof frame, b.board, seq_);
  }
  reply_.reset();
  hal::bus_write(frame, n);
  waiting_ = true;
  request_ms_ = now;
}

void Bridge::poll(uint32_t now) {
  if (armed_ && (uint32_t)(now - last_setpoint_ms_) > WATCHDOG_MS) {
    ++counters.watchdog_trips;
    disarm();
    if (ros_) ros_->close_gate(now);
  }
  if (waiting_ && (uint32_t)(now - request_ms_) > PIRATE_BUS_REPLY_TIMEOUT_MS) {
    ++counters.bus_timeouts;
    waiting_ = false;
    if (next_row_ < BOARD_COUNT) on_missed_reply(next_row_);
    ++next_row_;
  }
  if (waiting_) return;  // half duplex: never talk over a board's reply
  if (stop_pending_) {
    uint8_t frame[BUS_HEADER + 1];
    uint8_t n = bus_encode_stop(frame, sizeof frame, BUS_BROADCAST, ++seq_);
    hal::bus_write(frame, n);
    ++counters.stops_sent;
    stop_pending_ = false;
  }
  if (next_row_ >= BOARD_COUNT) {
    if ((uint32_t)(now - cycle_start_ms_) < CYCLE_MS) return;
    cycle_start_ms_ = now;
    next_row_ = 0;
  }
  request(next_row_, now);
}

void Bridge::on_bus_byte(uint8_t b, uint32_t now) {
  (void)now;
  if (!waiting_ || !reply_.feed(b)) return;
  if (next_row_ >= BOARD_COUNT || reply_.addr() != kBoards[next_row_].board ||
      reply_.seq() != seq_)
    return;  // not the board we asked: keep waiting until the timeout
  waiting_ = false;
  on_reply(next_row_);
  ++next_row_;
  if (publish_state(reply_.addr(), true)) ++counters.states;
}

// One Small State: the board's reply, or (not answered) the board +
// SMALL_STATE_NO_ANSWER with all data 0.
bool Bridge::publish_state(uint8_t board, bool answered) {
  uint8_t msg[1 + 2 * SMALL_STATE_SIZE];
  msg[0] = answered ? board : (uint8_t)(board | SMALL_STATE_NO_ANSWER);
  for (uint8_t i = 0; i < SMALL_STATE_SIZE; ++i) {
    uint16_t v = answered ? (uint16_t)reply_.data(i) : 0;
    msg[1 + 2 * i] = v & 0xFF;
    msg[2 + 2 * i] = v >> 8;
  }
  return ros_ && ros_->publish(TOPIC_SMALL_STATE_ID, msg, sizeof msg);
}

void Bridge::on_missed_reply(uint8_t row) {
  if (publish_state(kBoards[row].board, false)) ++counters.no_answers;
  if (missed_[row] < 255) ++missed_[row];
  if (missed_[row] >= BOARD_SILENT_AFTER && !reported_silent_[row] &&
      report(ROS_LOG_WARN, row, "not answering")) {
    reported_silent_[row] = true;  // once per episode, and only once the log went out
    ++counters.silent_reports;
  }
}

void Bridge::on_reply(uint8_t row) {
  missed_[row] = 0;
  if (reported_silent_[row] && report(ROS_LOG_INFO, row, "answering again"))
    reported_silent_[row] = false;
}

// "Pirate Bay: board 22 not answering": fixed text, the board id in digits.
bool Bridge::report(uint8_t level, uint8_t row, const char *what) {
  char text[48] = "Pirate Bay: board ";
  uint8_t n = (uint8_t)strlen(text);
  text[n++] = (char)('0' + kBoards[row].board / 10);
  text[n++] = (char)('0' + kBoards[row].board % 10);
  text[n++] = ' ';
  strncpy(text + n, what, sizeof text - n - 1);
  text[sizeof text - 1] = 0;
  return ros_ && ros_->log(level, text);
}
