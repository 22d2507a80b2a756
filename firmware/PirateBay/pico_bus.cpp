#include "pico_bus.h"

uint8_t bus_crc8(const uint8_t *data, uint8_t n) {
  uint8_t crc = 0;
  for (uint8_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (uint8_t bit = 0; bit < 8; ++bit)
      crc = (crc & 0x80) ? (uint8_t)((crc << 1) ^ 0x07) : (uint8_t)(crc << 1);
  }
  return crc;
}

static uint8_t finish(uint8_t *out, uint8_t addr, uint8_t kind, uint8_t seq, uint8_t len) {
  out[0] = BUS_START;
  out[1] = addr;
  out[2] = kind;
  out[3] = seq;
  out[4] = len;
  out[BUS_HEADER + len] = bus_crc8(out + 1, BUS_HEADER - 1 + len);
  return BUS_HEADER + len + 1;
}

uint8_t bus_encode_set(uint8_t *out, uint8_t cap, uint8_t addr, uint8_t seq, uint8_t mode0,
                       uint8_t mode1, int16_t setpoint0, int16_t setpoint1, uint16_t limit) {
  if (cap < BUS_HEADER + BUS_SET_LEN + 1) return 0;
  uint8_t *p = out + BUS_HEADER;
  p[0] = mode0;
  p[1] = mode1;
  p[2] = (uint16_t)setpoint0 & 0xFF;
  p[3] = (uint16_t)setpoint0 >> 8;
  p[4] = (uint16_t)setpoint1 & 0xFF;
  p[5] = (uint16_t)setpoint1 >> 8;
  p[6] = limit & 0xFF;
  p[7] = limit >> 8;
  return finish(out, addr, BUS_SET, seq, BUS_SET_LEN);
}

uint8_t bus_encode_stop(uint8_t *out, uint8_t cap, uint8_t addr, uint8_t seq) {
  if (cap < BUS_HEADER + 1) return 0;
  return finish(out, addr, BUS_STOP, seq, 0);
}

bool BusReplyParser::feed(uint8_t b) {
  switch (state_) {
    case START:
      if (b == BUS_START) {
        state_ = HEAD;
        pos_ = 0;
      }
      return false;
    case HEAD:
      frame_[pos_++] = b;
      if (pos_ == BUS_HEADER - 1) {
        if (frame_[1] != BUS_STATE || frame_[3] != BUS_STATE_LEN) {
          ++errors;
          state_ = START;
        } else {
          state_ = DATA;
        }
      }
      return false;
    case DATA:
      if (pos_ < sizeof frame_) frame_[pos_] = b;
      ++pos_;
      if (pos_ >= sizeof frame_) state_ = CRC;
      return false;
    case CRC:
      state_ = START;
      if (bus_crc8(frame_, sizeof frame_) != b) {
        ++errors;
        return false;
      }
      return true;
  }
  return false;
}

int16_t BusReplyParser::data(uint8_t i) const {
  if (i >= SMALL_STATE_SIZE) return 0;
  const uint8_t *p = frame_ + BUS_HEADER - 1 + 2 * i;
  return (int16_t)(p[0] | ((uint16_t)p[1] << 8));
}
