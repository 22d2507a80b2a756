// A scripted hardware layer for native unit tests and the fuzz harness:
// time is set by the test, bytes go through plain buffers.
#ifndef PIRATE_HAL_FAKE_H
#define PIRATE_HAL_FAKE_H

#include <stdint.h>

#include <deque>
#include <vector>

namespace fake {

extern uint32_t now_ms;
extern std::deque<uint8_t> link_in, bus_in;
extern std::vector<uint8_t> link_out, bus_out;
void reset();

}  // namespace fake

#endif
