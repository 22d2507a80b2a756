// RS485 bus to the PICO boards: frame encoding and the reply parser.
// Protocol: firmware/README.md ("PICO bus"); mirrored in
// src/pirate/sim/pico_bus.py.
#ifndef PIRATE_PICO_BUS_H
#define PIRATE_PICO_BUS_H

#include <stdint.h>

#include "pirate_generated.h"

#define BUS_HEADER 5
#define BUS_MAX_FRAME (BUS_HEADER + BUS_STATE_LEN + 1)

uint8_t bus_crc8(const uint8_t *data, uint8_t n);

// Frame builders: write into out (capacity cap), return the length, 0 if it
// does not fit.
uint8_t bus_encode_set(uint8_t *out, uint8_t cap, uint8_t addr, uint8_t seq, uint8_t mode0,
                       uint8_t mode1, int16_t setpoint0, int16_t setpoint1, uint16_t limit);
uint8_t bus_encode_stop(uint8_t *out, uint8_t cap, uint8_t addr, uint8_t seq);

// Byte-at-a-time parser of board replies (STATE frames only).
class BusReplyParser {
 public:
  BusReplyParser() : errors(0), state_(START), pos_(0) {}
  // True when b completed a valid STATE frame; then addr(), seq(), data() hold it.
  bool feed(uint8_t b);
  void reset() { state_ = START; }
  uint8_t addr() const { return frame_[0]; }
  uint8_t seq() const { return frame_[2]; }
  int16_t data(uint8_t i) const;  // i < SMALL_STATE_SIZE, else 0
  uint16_t errors;

 private:
  enum State { START, HEAD, DATA, CRC };
  State state_;
  uint8_t pos_;
  uint8_t frame_[BUS_HEADER - 1 + BUS_STATE_LEN];  // addr type seq len payload
};

#endif
