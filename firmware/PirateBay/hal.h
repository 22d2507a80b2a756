// Hardware layer: the only functions the firmware logic calls to touch the
// world. hal_avr.cpp implements them on the Mega (USB Serial to the laptop,
// Serial1 + a driver-enable pin for the RS485 bus); firmware/native has a
// Linux implementation (pipes/sockets, for firmware-in-the-loop) and a fake
// one (for unit tests and the fuzz harness).
#ifndef PIRATE_HAL_H
#define PIRATE_HAL_H

#include <stdint.h>

namespace hal {

void begin();                                    // open ports, set pins
uint32_t millis();                               // monotonic ms, wraps
int link_read();                                 // next byte from the laptop, -1 if none
void link_write(const uint8_t *data, uint16_t n);
int bus_read();                                  // next byte from the RS485 bus, -1 if none
void bus_write(const uint8_t *data, uint16_t n); // whole frame, drives DE around it
void idle();                                     // nothing to do for now (native: wait)

}  // namespace hal

#endif
