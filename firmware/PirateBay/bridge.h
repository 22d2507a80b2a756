// The bridge: laptop arrays in (rosserial), PICO board commands out (RS485),
// board state back as one Small State per board.
//
// Safety rules (report 7.2):
// - after power-up, a reset or any new handshake the boards get STOP until a
//   fresh setpoint array arrives ("armed");
// - no setpoint array for WATCHDOG_MS, or the link lost: disarm and send
//   every board STOP at once (a broadcast), then STOP in every refresh;
//   a watchdog trip keeps the link up but closes the device's freshness
//   gate (rosserial_device.h), so a setpoint the link buffered during an
//   outage is never applied: only one written after the host answered a
//   time request we sent after the trip re-arms;
// - the laptop's command state comes first: after power-up
//   nothing is armed until a control array AND a limits array have
//   arrived, so the boards never run setpoints in modes or limits the
//   laptop did not send. Control and limits are state, not a stream: they
//   are applied whenever they arrive checked (the link is FIFO, so the
//   newest arrives last) and kept through trips and renegotiations;
// - every array is length-checked, every control code range-checked; a bad
//   message is dropped whole and counted, the previous values stay;
// - a board that does not answer a request is published in its place as a
//   Small State of board + SMALL_STATE_NO_ANSWER with all data 0, so the
//   laptop tells a silent board from a Small State the link lost;
// - a board that misses BOARD_SILENT_AFTER replies in a row is reported
//   once per episode as a rosserial WARN log naming it, and its return as
//   INFO.
#ifndef PIRATE_BRIDGE_H
#define PIRATE_BRIDGE_H

#include <stdint.h>

#include "pico_bus.h"
#include "pirate_generated.h"
#include "rosserial_device.h"

// 300 ms budget from the last valid message to every board safe,
// less the time to notice (one loop) and to send the broadcast (~1 ms),
// less one bus reply timeout the broadcast may wait for
// (measurements.md#link-command-loss).
#define WATCHDOG_MS 250
#define BOARD_SILENT_AFTER 2       // consecutive missed replies = a silent board
#define CYCLE_MS 100               // refresh of all nine boards, ~10 Hz (SPEC 2)
#ifndef PIRATE_BUS_REPLY_TIMEOUT_MS
#define PIRATE_BUS_REPLY_TIMEOUT_MS BUS_REPLY_TIMEOUT_MS
#endif

struct BridgeCounters {
  uint16_t setpoints, controls, limits, rejected, watchdog_trips, stops_sent,
      bus_timeouts, states, no_answers, stale_setpoints, silent_reports;
};

class Bridge : public RosHandler {
 public:
  Bridge();
  void attach(RosserialDevice *ros) { ros_ = ros; }
  void poll(uint32_t now);
  void on_bus_byte(uint8_t b, uint32_t now);

  void on_message(uint16_t topic, const uint8_t *payload, uint16_t len, bool fresh,
                  uint32_t now);
  void on_configured(uint32_t now);
  void on_unconfigured(uint32_t now);

  bool armed() const { return armed_; }
  int16_t setpoint(uint8_t i) const { return i < SETPOINT_SIZE ? setpoint_[i] : 0; }
  BridgeCounters counters;

 private:
  void disarm();
  void request(uint8_t row, uint32_t now);
  void on_missed_reply(uint8_t row);
  void on_reply(uint8_t row);
  bool publish_state(uint8_t board, bool answered);
  bool report(uint8_t level, uint8_t row, const char *what);

  RosserialDevice *ros_;
  int16_t setpoint_[SETPOINT_SIZE];
  int16_t control_[CONTROL_SIZE];
  uint16_t limit_[LIMIT_SIZE];
  bool armed_, stop_pending_, waiting_, control_known_, limits_known_;
  uint8_t missed_[BOARD_COUNT];
  bool reported_silent_[BOARD_COUNT];
  uint32_t last_setpoint_ms_, cycle_start_ms_, request_ms_;
  uint8_t next_row_, seq_;
  BusReplyParser reply_;
};

#endif
