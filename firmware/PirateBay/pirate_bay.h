// The whole firmware as one object: rosserial device + bridge, stepped by
// the sketch's loop() on the Mega and by main() on Linux.
#ifndef PIRATE_PIRATE_BAY_H
#define PIRATE_PIRATE_BAY_H

#include "bridge.h"
#include "hal.h"
#include "rosserial_device.h"

class PirateBay {
 public:
  PirateBay() : ros(&bridge) { bridge.attach(&ros); }

  // One pass: drain both ports, then run the timers. Bytes are handled as
  // they come so the Mega's 64-byte serial buffers never overflow.
  void step() {
    int c;
    uint32_t now = hal::millis();
    while ((c = hal::link_read()) >= 0) ros.feed((uint8_t)c, now);
    while ((c = hal::bus_read()) >= 0) bridge.on_bus_byte((uint8_t)c, now);
    ros.poll(now);
    bridge.poll(now);
  }

  Bridge bridge;
  RosserialDevice ros;
};

#endif
