// Hardware layer for the Arduino Mega 2560: Serial (USB) to the laptop,
// Serial1 to the RS485 transceiver whose driver-enable is on BUS_DE_PIN.
#ifdef ARDUINO
#include <Arduino.h>

#include "hal.h"
#include "pirate_generated.h"

#ifndef LINK_BAUD
#define LINK_BAUD 57600UL  // rosserial's default; build with LINK_BAUD=115200 to change
#endif
#define BUS_DE_PIN 2       // RS485 driver enable (high = transmit)

namespace hal {

void begin() {
  pinMode(BUS_DE_PIN, OUTPUT);
  digitalWrite(BUS_DE_PIN, LOW);
  Serial.begin(LINK_BAUD);
  Serial1.begin(BUS_BAUD);
}

uint32_t millis() { return ::millis(); }

int link_read() { return Serial.read(); }

void link_write(const uint8_t *data, uint16_t n) { Serial.write(data, n); }

int bus_read() { return Serial1.read(); }

void bus_write(const uint8_t *data, uint16_t n) {
  digitalWrite(BUS_DE_PIN, HIGH);
  Serial1.write(data, n);
  Serial1.flush();  // wait for the last stop bit before releasing the bus
  digitalWrite(BUS_DE_PIN, LOW);
}

void idle() {}

}  // namespace hal
#endif
