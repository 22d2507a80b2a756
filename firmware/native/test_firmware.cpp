// Native unit tests of the firmware logic over the fake hardware layer.
// Prints one line per failed check and a summary "N passed, N failed".
#include <stdio.h>
#include <string.h>

#include <string>
#include <vector>

#include "frames.h"
#include "hal_fake.h"
#include "pirate_bay.h"

static int passed = 0, failed = 0;
#define CHECK(cond)                                                   \
  do {                                                                \
    if (cond) ++passed;                                               \
    else { ++failed; printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond); } \
  } while (0)

struct BusFrame {
  uint32_t t;
  uint8_t addr, type;
  std::vector<uint8_t> payload;
};

// Simulated boards: record every master frame, answer addressed ones.
struct Boards {
  std::vector<BusFrame> seen;
  size_t pos = 0;
  int muted = -1;  // a board that does not answer
  void serve() {
    std::vector<uint8_t> &b = fake::bus_out;
    while (pos + 6 <= b.size()) {
      if (b[pos] != 0xA5) { ++pos; continue; }
      uint8_t len = b[pos + 4];
      if (pos + 6 + len > b.size()) break;
      BusFrame f = {fake::now_ms, b[pos + 1], b[pos + 2],
                    std::vector<uint8_t>(b.begin() + pos + 5, b.begin() + pos + 5 + len)};
      uint8_t seq = b[pos + 3];
      pos += 6 + len;
      seen.push_back(f);
      if (f.addr == 0xFF || f.addr == muted) continue;
      std::vector<uint8_t> reply = {0xA5, f.addr, 0x81, seq, 18};
      for (int i = 0; i < 9; ++i) { reply.push_back(f.addr); reply.push_back(i); }
      reply.push_back(bus_crc8(reply.data() + 1, (uint8_t)(reply.size() - 1)));
      fake::bus_in.insert(fake::bus_in.end(), reply.begin(), reply.end());
    }
  }
  int count(uint8_t type, uint32_t since = 0, int addr = -1) const {
    int n = 0;
    for (const BusFrame &f : seen)
      if (f.type == type && f.t >= since && (addr < 0 || f.addr == addr)) ++n;
    return n;
  }
  const BusFrame *last_set(uint8_t addr) const {
    for (size_t i = seen.size(); i-- > 0;)
      if (seen[i].type == BUS_SET && seen[i].addr == addr) return &seen[i];
    return 0;
  }
};

static int16_t i16(const std::vector<uint8_t> &p, int i) { return (int16_t)(p[2 * i] | (p[2 * i + 1] << 8)); }

static const std::vector<int> kSetpoints = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 50, 13};
static const std::vector<int> kControl = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
static const std::vector<int> kLimits = {65535, 65535, 65535, 65535};

struct Rig {
  PirateBay bay;
  Boards boards;
  size_t answered = 0;     // link frames already looked at by the host
  bool answer_time = true; // the host answers every time request
  Rig() { fake::reset(); }
  void send(const std::vector<uint8_t> &bytes) { fake::link_in.insert(fake::link_in.end(), bytes.begin(), bytes.end()); }
  // The host's side: answer each new time request, as rosserial_python does.
  void host() {
    auto frames = link_frames();
    for (; answered < frames.size(); ++answered)
      if (answer_time && frames[answered].first == 10) send(ros_frame(10, {1, 0, 0, 0, 0, 0, 0, 0}));
  }
  void run(uint32_t ms) {
    for (uint32_t i = 0; i < ms; ++i) {
      bay.step();
      boards.serve();
      bay.step();
      host();
      ++fake::now_ms;
    }
  }
  void handshake() {
    send(ros_frame(0, {}));
    run(5);
  }
  void state(const std::vector<int> &control, const std::vector<int> &limits) {
    send(ros_frame(TOPIC_CONTROL_ID, int16_payload(control)));
    send(ros_frame(TOPIC_LIMITS_ID, int16_payload(limits)));
  }
  void arm() {  // the laptop after Play: control, limits, setpoints
    handshake();
    state(kControl, kLimits);
    setpoints(kSetpoints);
  }
  void setpoints(const std::vector<int> &v) { send(ros_frame(TOPIC_SETPOINT_ID, int16_payload(v))); }
  // Frames the firmware sent to the laptop, as (topic, payload).
  std::vector<std::pair<uint16_t, std::vector<uint8_t> > > link_frames() const {
    std::vector<std::pair<uint16_t, std::vector<uint8_t> > > out;
    const std::vector<uint8_t> &b = fake::link_out;
    for (size_t p = 0; p + 8 <= b.size();) {
      uint16_t len = b[p + 2] | (b[p + 3] << 8);
      if (b[p] != 0xFF || b[p + 1] != 0xFE || p + 8 + len > b.size()) { ++p; continue; }
      out.push_back(std::make_pair((uint16_t)(b[p + 5] | (b[p + 6] << 8)),
                                   std::vector<uint8_t>(b.begin() + p + 7, b.begin() + p + 7 + len)));
      p += 8 + len;
    }
    return out;
  }
  // Texts of the rosserial logs (topic 7) at `level` the firmware sent.
  std::vector<std::string> logs(uint8_t level) const {
    std::vector<std::string> out;
    for (auto &f : link_frames())
      if (f.first == 7 && f.second.size() >= 5 && f.second[0] == level)
        out.push_back(std::string(f.second.begin() + 5, f.second.end()));
    return out;
  }
};

static void test_power_up_never_moves() {
  Rig r;
  r.run(2000);
  CHECK(r.boards.count(BUS_SET) == 0);
  CHECK(r.boards.count(BUS_STOP) >= 9 * 19);
  r.setpoints(kSetpoints);  // before any handshake: ignored
  r.run(300);
  CHECK(r.boards.count(BUS_SET) == 0);
}

static void test_handshake_announces_topics_with_our_md5() {
  Rig r;
  r.answer_time = false;
  r.send(ros_frame(0, {}));
  r.run(2);
  auto frames = r.link_frames();
  int pubs = 0, subs = 0, time_requests = 0;
  std::string all;
  for (auto &f : frames) {
    if (f.first == 0) ++pubs;
    if (f.first == 1) ++subs;
    if (f.first == 10 && f.second.size() == 8) ++time_requests;  // a std_msgs/Time, as ros_lib
    all += std::string(f.second.begin(), f.second.end());
  }
  CHECK(pubs >= 1 && subs >= 3 && time_requests >= 1);
  // TopicInfo ends with the buffer for that direction: 112 out, 64 in.
  for (auto &f : frames) {
    if (f.first > 1 || f.second.size() < 4) continue;
    uint32_t size = f.second[f.second.size() - 4] | (f.second[f.second.size() - 3] << 8);
    CHECK(size == (f.first == 0 ? ROS_OUT_BUF : ROS_IN_BUF));
  }
  CHECK(all.find(TOPIC_SETPOINT_MD5) != std::string::npos);
  CHECK(all.find(TOPIC_SMALL_STATE_NAME) != std::string::npos);
  CHECK(!r.bay.ros.configured());
  r.state(kControl, kLimits);
  r.setpoints(kSetpoints);  // before the time reply: not configured, not applied
  r.run(150);
  CHECK(r.boards.count(BUS_SET) == 0);
  r.answer_time = true;
  r.run(600);  // the next announcement gets its answer
  CHECK(r.bay.ros.configured());
  r.run(300);  // configured but no fresh setpoint yet
  CHECK(r.boards.count(BUS_SET) == 0);
}

static void test_unconfigured_device_announces_itself() {
  Rig r;
  r.answer_time = false;
  r.run(1200);  // nobody asked: power-up and every 500 ms after
  int announcements = 0;
  for (auto &f : r.link_frames())
    if (f.first == 0) ++announcements;
  CHECK(announcements == 3);
  r.answer_time = true;  // a host that only answers time requests (rosserial_python)
  r.run(600);
  CHECK(r.bay.ros.configured());
}

static void test_setpoints_reach_boards_with_wheel_signs() {
  Rig r;
  r.arm();
  r.run(110);
  const int8_t expect_sign[9] = {0, 0, 1, -1, 1, 1, -1, 1, 0};
  for (int k = 0; k < 9; ++k) {
    const BusFrame *f = r.boards.last_set(20 + k);
    CHECK(f != 0);
    if (!f) continue;
    CHECK(i16(f->payload, 1) == kSetpoints[k]);               // setpoint0 = element k
    if (expect_sign[k]) CHECK(i16(f->payload, 2) == expect_sign[k] * 50);
  }
  CHECK(i16(r.boards.last_set(20)->payload, 2) == 10);   // camera pan, element 9
  CHECK(i16(r.boards.last_set(28)->payload, 2) == 13);   // rear LED, element 12
  CHECK((uint16_t)i16(r.boards.last_set(22)->payload, 3) == 65535);  // no limit
  int states = 0;
  for (auto &f : r.link_frames())
    if (f.first == TOPIC_SMALL_STATE_ID && f.second.size() == 19 && f.second[0] >= 20 && f.second[0] <= 28) ++states;
  CHECK(states >= 9);
}

// After power-up (a Mega reset) setpoints alone never move a
// board: the control and limits arrays must have arrived first.
static void test_reset_holds_boards_until_control_and_limits() {
  Rig r;
  r.handshake();
  for (int i = 0; i < 5; ++i) {
    r.setpoints(kSetpoints);
    r.run(100);
  }
  CHECK(r.boards.count(BUS_SET) == 0);
  r.send(ros_frame(TOPIC_CONTROL_ID, int16_payload({2, 2, 3, 3, 0, 2, 3, 3, 1, 2, 0, 1})));
  r.setpoints(kSetpoints);
  r.run(100);
  CHECK(r.boards.count(BUS_SET) == 0);  // limits still unknown
  r.send(ros_frame(TOPIC_LIMITS_ID, int16_payload({100, 200, 300, 400})));
  uint32_t t = fake::now_ms;
  r.setpoints(kSetpoints);
  r.run(110);
  const BusFrame *b23 = r.boards.last_set(23);
  CHECK(r.boards.count(BUS_SET, t) >= 9);
  CHECK(b23 && b23->payload[0] == 3 && i16(b23->payload, 3) == 200);
}

static uint32_t first_broadcast_stop_after(const Rig &r, uint32_t t) {
  for (auto &f : r.boards.seen)
    if (f.type == BUS_STOP && f.addr == 0xFF && f.t > t) return f.t;
  return 0;
}

static void test_watchdog_stops_every_board_and_keeps_the_link() {
  Rig r;
  r.arm();
  r.run(1);
  uint32_t last = fake::now_ms;
  r.run(400);
  uint32_t stop_at = first_broadcast_stop_after(r, last);
  CHECK(stop_at > last && stop_at - last <= 300);
  CHECK(stop_at - last >= WATCHDOG_MS);
  CHECK(r.boards.count(BUS_SET, stop_at) == 0);
  CHECK(r.bay.bridge.counters.watchdog_trips == 1);
  CHECK(r.bay.ros.configured());    // the link stays up: state keeps flowing
  size_t frames = r.link_frames().size();
  r.run(200);
  CHECK(r.link_frames().size() > frames + 9);
  uint32_t rearm = fake::now_ms;
  r.setpoints(kSetpoints);          // written after the host answered: re-arms
  r.run(110);
  CHECK(r.boards.count(BUS_SET, rearm) >= 9);
}

// The freshness rule: bytes written before the trip, and a time reply that
// answers a request sent before the trip, never re-arm.
static void test_trip_never_applies_bytes_from_before() {
  Rig r;
  r.arm();
  r.answer_time = false;  // a stall: the host sees our requests late
  for (int i = 0; i < 11; ++i) {  // the periodic sync request goes out unanswered
    r.setpoints(kSetpoints);
    r.run(100);
  }
  uint32_t trip_from = fake::now_ms;
  r.run(400);             // the trip, with that request still in flight
  CHECK(first_broadcast_stop_after(r, trip_from) != 0);
  r.send(ros_frame(10, {2, 0, 0, 0, 0, 0, 0, 0}));  // the host's answer to a pre-trip request
  r.setpoints(kSetpoints);                            // ... and a setpoint written before the trip
  r.run(5);
  uint32_t t = fake::now_ms;
  r.run(110);
  CHECK(r.boards.count(BUS_SET, t) == 0);
  CHECK(r.bay.bridge.counters.stale_setpoints >= 1);
  r.answer_time = true;   // now the host answers what we asked after the trip
  r.run(300);
  t = fake::now_ms;
  r.setpoints(kSetpoints);
  r.run(110);
  CHECK(r.boards.count(BUS_SET, t) >= 9);
}

static void test_corrupt_and_malformed_frames_change_nothing() {
  Rig r;
  r.arm();
  r.run(5);
  std::vector<uint8_t> bad = ros_frame(TOPIC_SETPOINT_ID, int16_payload({9, 9, 9, 9, 9, 9, 9, 9, 9, 9, 9, 9, 9}));
  bad[10] ^= 0x04;
  r.send(bad);
  std::vector<int> short_array(kSetpoints.begin(), kSetpoints.end() - 1);
  r.send(ros_frame(TOPIC_SETPOINT_ID, int16_payload(short_array)));   // 12 elements
  r.send(ros_frame(TOPIC_CONTROL_ID, int16_payload({0, 0, 0, 0, 0, 0, 0, 0, 11, 0, 0, 0})));  // code 11
  r.send(ros_frame(TOPIC_CONTROL_ID, int16_payload({0, 0, 0, 0, 0, 0, 0, 0, -1, 0, 0, 0})));
  r.run(5);
  for (int i = 0; i < SETPOINT_SIZE; ++i) CHECK(r.bay.bridge.setpoint(i) == kSetpoints[i]);
  CHECK(r.bay.ros.counters.checksum_errors == 1);
  CHECK(r.bay.bridge.counters.rejected == 3);
  CHECK(r.bay.bridge.setpoint(200) == 0);  // out-of-range index reads as 0
}

static void test_modes_and_limits_forwarded() {
  Rig r;
  r.handshake();
  r.state({2, 2, 3, 3, 0, 2, 3, 3, 7, 2, 0, 1}, {100, 200, 300, 400});
  r.setpoints(kSetpoints);
  r.run(110);
  const BusFrame *b23 = r.boards.last_set(23);
  CHECK(b23 && b23->payload[0] == 3 && b23->payload[1] == 1 && i16(b23->payload, 3) == 200);
  const BusFrame *b28 = r.boards.last_set(28);
  CHECK(b28 && b28->payload[0] == 7);   // command code travels at index 8
  CHECK(i16(r.boards.last_set(27)->payload, 3) == 400);
}

static void test_tx_stop_and_silence_disarm() {
  Rig r;
  r.arm();
  r.run(50);
  r.send(ros_frame(11, {}));
  r.run(1);
  CHECK(!r.bay.bridge.armed() && !r.bay.ros.configured());
  r.run(600);  // announces itself; the host answers its time request
  CHECK(r.bay.ros.configured());
  r.answer_time = false;
  r.run(3100);  // host silent beyond ROS_LINK_TIMEOUT_MS
  CHECK(!r.bay.ros.configured());
}

// A board that stops answering is reported once per episode.
static void test_silent_board_reported_once_per_episode() {
  Rig r;
  r.arm();
  for (int i = 0; i < 3; ++i) {
    r.setpoints(kSetpoints);
    r.run(100);
  }
  CHECK(r.logs(ROS_LOG_WARN).empty());
  r.boards.muted = 22;
  for (int i = 0; i < 10; ++i) {
    r.setpoints(kSetpoints);
    r.run(100);
  }
  auto warns = r.logs(ROS_LOG_WARN);
  CHECK(warns.size() == 1);
  CHECK(!warns.empty() && warns[0] == "Pirate Bay: board 22 not answering");
  r.boards.muted = -1;
  r.setpoints(kSetpoints);
  r.run(200);
  auto infos = r.logs(ROS_LOG_INFO);
  CHECK(infos.size() == 1 && infos[0] == "Pirate Bay: board 22 answering again");
  r.boards.muted = 22;  // a second episode is reported again
  r.setpoints(kSetpoints);
  r.run(250);
  CHECK(r.logs(ROS_LOG_WARN).size() == 2);
}

// A board that does not answer is published in its place, data 0, every
// cycle: the laptop tells it from a Small State the link lost.
static void test_unanswered_board_published_with_the_no_answer_mark() {
  Rig r;
  r.arm();
  r.run(300);
  r.boards.muted = 27;
  size_t before = r.link_frames().size();
  for (int i = 0; i < 5; ++i) {
    r.setpoints(kSetpoints);
    r.run(100);
  }
  int marked = 0, of_27 = 0, others = 0;
  auto frames = r.link_frames();
  for (size_t k = before; k < frames.size(); ++k) {
    const std::vector<uint8_t> &p = frames[k].second;
    if (frames[k].first != TOPIC_SMALL_STATE_ID || p.size() != 19) continue;
    bool zeros = true;
    for (size_t i = 1; i < p.size(); ++i) zeros = zeros && p[i] == 0;
    if (p[0] == (27 | SMALL_STATE_NO_ANSWER) && zeros) ++marked;
    else if (p[0] == 27) ++of_27;
    else if (p[0] >= 20 && p[0] <= 28) ++others;
  }
  CHECK(marked >= 4 && marked <= 6);
  CHECK(of_27 == 0);
  CHECK(others >= 8 * 4);
  CHECK(r.bay.bridge.counters.no_answers == (uint16_t)marked);
}

static void test_bus_crc_and_layout_match_python() {
  // CRC-8/SMBUS check value, as test/unit/test_firmware_bus.py asserts for Python.
  CHECK(bus_crc8((const uint8_t *)"123456789", 9) == 0xF4);
  uint8_t f[BUS_MAX_FRAME];
  uint8_t n = bus_encode_set(f, sizeof f, 23, 7, 3, 1, -256, -50, 200);
  const uint8_t expect[13] = {0xA5, 23, 0x01, 7, 8, 3, 1, 0x00, 0xFF, 0xCE, 0xFF, 200, 0};
  CHECK(n == 14 && memcmp(f, expect, 13) == 0 && f[13] == bus_crc8(f + 1, 12));
  CHECK(bus_encode_set(f, 10, 23, 7, 3, 1, 0, 0, 0) == 0);  // does not fit: refused
}

int main() {
  test_bus_crc_and_layout_match_python();
  test_power_up_never_moves();
  test_handshake_announces_topics_with_our_md5();
  test_unconfigured_device_announces_itself();
  test_setpoints_reach_boards_with_wheel_signs();
  test_reset_holds_boards_until_control_and_limits();
  test_watchdog_stops_every_board_and_keeps_the_link();
  test_trip_never_applies_bytes_from_before();
  test_corrupt_and_malformed_frames_change_nothing();
  test_modes_and_limits_forwarded();
  test_tx_stop_and_silence_disarm();
  test_silent_board_reported_once_per_episode();
  test_unanswered_board_published_with_the_no_answer_mark();
  printf("firmware unit: %d passed, %d failed\n", passed, failed);
  return failed ? 1 : 0;
}
