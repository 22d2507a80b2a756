// Test helpers: rosserial frames and bus frames written independently of
// the firmware's own encoder, straight from the protocol definitions.
#ifndef PIRATE_TEST_FRAMES_H
#define PIRATE_TEST_FRAMES_H

#include <stdint.h>

#include <vector>

inline std::vector<uint8_t> ros_frame(uint16_t topic, const std::vector<uint8_t> &payload) {
  uint16_t len = (uint16_t)payload.size();
  std::vector<uint8_t> f = {0xFF, 0xFE, (uint8_t)(len & 0xFF), (uint8_t)(len >> 8)};
  f.push_back((uint8_t)(255 - ((f[2] + f[3]) % 256)));
  f.push_back(topic & 0xFF);
  f.push_back(topic >> 8);
  unsigned sum = f[5] + f[6];
  for (uint8_t b : payload) {
    f.push_back(b);
    sum += b;
  }
  f.push_back((uint8_t)(255 - sum % 256));
  return f;
}

inline std::vector<uint8_t> int16_payload(const std::vector<int> &values) {
  std::vector<uint8_t> p;
  for (int v : values) {
    p.push_back((uint8_t)(v & 0xFF));
    p.push_back((uint8_t)((v >> 8) & 0xFF));
  }
  return p;
}

// True when the last bytes of `stream` are a whole, correctly checksummed
// frame on `topic` with exactly `payload` (the fuzz oracle).
inline bool ends_with_valid_frame(const std::vector<uint8_t> &stream, uint16_t topic,
                                  const std::vector<uint8_t> &payload) {
  std::vector<uint8_t> f = ros_frame(topic, payload);
  if (stream.size() < f.size()) return false;
  return std::equal(f.begin(), f.end(), stream.end() - f.size());
}

#endif
