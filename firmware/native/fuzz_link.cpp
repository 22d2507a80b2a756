// Byte-stream fuzz harness of the firmware's rosserial parser and bridge,
// built with AddressSanitizer + UBSan (clang's libFuzzer runtime is not
// installed on the build machine, so this is a plain seeded harness; the
// entry point has libFuzzer's signature and links with -fsanitize=fuzzer
// where that exists, with -DPLAIN_HARNESS providing main() otherwise).
//
// Property checked after every byte: the bridge's setpoints change only
// when the bytes fed so far end with a whole, correctly checksummed
// SetpointArray frame carrying exactly the new values (an oracle written
// independently in frames.h). Out-of-bounds access aborts under ASan.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <random>
#include <vector>

#include "frames.h"
#include "hal_fake.h"
#include "pirate_bay.h"

static void fail(const char *why) {
  fprintf(stderr, "FUZZ FAILURE: %s\n", why);
  abort();
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fake::reset();
  static PirateBay *bay_storage = 0;
  delete bay_storage;
  bay_storage = new PirateBay();
  PirateBay &bay = *bay_storage;
  std::vector<uint8_t> fed;
  std::vector<uint8_t> start = ros_frame(0, {});
  std::vector<uint8_t> time = ros_frame(10, {0, 0, 0, 0, 0, 0, 0, 0});
  std::vector<uint8_t> control = ros_frame(TOPIC_CONTROL_ID, int16_payload({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
  std::vector<uint8_t> limits = ros_frame(TOPIC_LIMITS_ID, int16_payload({1, 1, 1, 1}));
  std::vector<uint8_t> initial = ros_frame(TOPIC_SETPOINT_ID, int16_payload({7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7}));
  for (auto *part : {&start, &time, &control, &limits, &initial})
    for (uint8_t b : *part) {
      bay.ros.feed(b, fake::now_ms);
      fed.push_back(b);
    }
  if (!bay.bridge.armed()) fail("handshake + control + limits + setpoint did not arm");
  int16_t before[SETPOINT_SIZE];
  for (int i = 0; i < SETPOINT_SIZE; ++i) before[i] = bay.bridge.setpoint(i);
  for (size_t k = 0; k < size; ++k) {
    fake::link_in.push_back(data[k]);
    fed.push_back(data[k]);
    if (k % 16 == 0) ++fake::now_ms;  // time moves: byte timeouts, watchdog
    bay.step();
    fake::bus_out.clear();
    fake::link_out.clear();
    bool changed = false;
    std::vector<int> now_values;
    for (int i = 0; i < SETPOINT_SIZE; ++i) {
      now_values.push_back(bay.bridge.setpoint(i));
      changed = changed || bay.bridge.setpoint(i) != before[i];
    }
    if (changed && !ends_with_valid_frame(fed, TOPIC_SETPOINT_ID, int16_payload(now_values)))
      fail("setpoints changed without a valid setpoint frame");
    for (int i = 0; i < SETPOINT_SIZE; ++i) before[i] = bay.bridge.setpoint(i);
  }
  return 0;
}

#ifdef PLAIN_HARNESS
// Streams: random bytes biased to the sync/version bytes, and valid frames
// (setpoint, control, limits, time, topic request) damaged by bit flips,
// insertions, deletions and truncation, concatenated.
int main(int argc, char **argv) {
  unsigned long runs = argc > 1 ? strtoul(argv[1], 0, 10) : 20000;
  std::mt19937 rng(20160705);
  auto r = [&](unsigned n) { return (unsigned)(rng() % n); };
  unsigned long bytes = 0;
  for (unsigned long run = 0; run < runs; ++run) {
    std::vector<uint8_t> s;
    unsigned parts = 1 + r(4);
    for (unsigned p = 0; p < parts; ++p) {
      if (r(3) == 0) {
        unsigned n = r(40);
        for (unsigned i = 0; i < n; ++i) {
          unsigned c = r(4);
          s.push_back(c == 0 ? 0xFF : c == 1 ? 0xFE : (uint8_t)r(256));
        }
        continue;
      }
      static const uint16_t topics[] = {TOPIC_SETPOINT_ID, TOPIC_CONTROL_ID, TOPIC_LIMITS_ID, 10, 0, 11, 1};
      uint16_t topic = topics[r(7)];
      unsigned count = topic == TOPIC_SETPOINT_ID ? SETPOINT_SIZE : topic == TOPIC_CONTROL_ID ? CONTROL_SIZE
                       : topic == TOPIC_LIMITS_ID ? LIMIT_SIZE : topic == 10 ? 4 : 0;
      if (r(8) == 0) count = r(40);  // wrong length, possibly beyond the buffer
      std::vector<int> values;
      for (unsigned i = 0; i < count; ++i) values.push_back((int)r(65536) - 32768);
      std::vector<uint8_t> f = ros_frame(topic, int16_payload(values));
      unsigned damage = r(3);
      for (unsigned d = 0; d < damage && !f.empty(); ++d) {
        unsigned pos = r(f.size());
        switch (r(4)) {
          case 0: f[pos] ^= (uint8_t)(1u << r(8)); break;
          case 1: f.insert(f.begin() + pos, (uint8_t)r(256)); break;
          case 2: f.erase(f.begin() + pos); break;
          case 3: f.resize(pos); break;
        }
      }
      s.insert(s.end(), f.begin(), f.end());
    }
    bytes += s.size();
    LLVMFuzzerTestOneInput(s.data(), s.size());
  }
  printf("firmware fuzz: %lu streams, %lu bytes, no failure\n", runs, bytes);
  return 0;
}
#endif
