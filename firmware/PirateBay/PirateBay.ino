// Pirate Bay: the Arduino Mega bridge between the laptop (rosserial over
// USB) and the nine PICO boards (RS485). See firmware/README.md.
#include "pirate_bay.h"

static PirateBay bay;

void setup() { hal::begin(); }

void loop() {
  bay.step();
  hal::idle();
}
