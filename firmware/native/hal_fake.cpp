#include "hal_fake.h"

#include "hal.h"

namespace fake {

uint32_t now_ms = 0;
std::deque<uint8_t> link_in, bus_in;
std::vector<uint8_t> link_out, bus_out;

void reset() {
  now_ms = 0;
  link_in.clear();
  bus_in.clear();
  link_out.clear();
  bus_out.clear();
}

}  // namespace fake

namespace hal {

void begin() {}
uint32_t millis() { return fake::now_ms; }

static int pop(std::deque<uint8_t> &q) {
  if (q.empty()) return -1;
  int b = q.front();
  q.pop_front();
  return b;
}

int link_read() { return pop(fake::link_in); }
void link_write(const uint8_t *d, uint16_t n) { fake::link_out.insert(fake::link_out.end(), d, d + n); }
int bus_read() { return pop(fake::bus_in); }
void bus_write(const uint8_t *d, uint16_t n) { fake::bus_out.insert(fake::bus_out.end(), d, d + n); }
void idle() {}

}  // namespace hal
