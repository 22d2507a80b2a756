// Native firmware for firmware-in-the-loop: the same PirateBay object the
// Mega runs, over hal_linux.cpp. Prints its counters to stderr on SIGTERM.
// Usage: pirate_bay_native [BUS_FD]   (link on stdin/stdout; bus fd default 3)
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>

#include "pirate_bay.h"

extern int hal_linux_bus_fd;

static volatile sig_atomic_t stop_requested = 0;

static void on_signal(int) { stop_requested = 1; }

int main(int argc, char **argv) {
  if (argc > 1) hal_linux_bus_fd = atoi(argv[1]);
  signal(SIGTERM, on_signal);
  signal(SIGINT, on_signal);
  signal(SIGPIPE, SIG_IGN);
  hal::begin();
  static PirateBay bay;
  while (!stop_requested) {
    bay.step();
    hal::idle();
  }
  const BridgeCounters &b = bay.bridge.counters;
  const RosCounters &r = bay.ros.counters;
  fprintf(stderr,
          "pirate_bay_native: frames in %u out %u, checksum errors %u, setpoints %u, "
          "rejected %u, watchdog trips %u, stops %u, bus timeouts %u, states %u\n",
          r.frames_in, r.frames_out, r.checksum_errors, b.setpoints, b.rejected,
          b.watchdog_trips, b.stops_sent, b.bus_timeouts, b.states);
  return 0;
}
