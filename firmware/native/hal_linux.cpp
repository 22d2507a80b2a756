// Hardware layer for Linux (firmware-in-the-loop): the laptop link is
// stdin/stdout (the FIL runner connects them to a pseudo-terminal), the
// RS485 bus is a socket to the simulated PICO boards, file descriptor
// hal_linux_bus_fd (set by main from argv, default 3).
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include "hal.h"

namespace {

const int kLinkIn = 0, kLinkOut = 1;

struct Input {
  int fd;
  uint8_t buf[256];
  ssize_t len, pos;
};
Input link_in = {kLinkIn, {0}, 0, 0};
Input bus_in = {3, {0}, 0, 0};

int next_byte(Input &in) {
  if (in.pos >= in.len) {
    in.len = read(in.fd, in.buf, sizeof in.buf);
    in.pos = 0;
    if (in.len == 0) {
      fprintf(stderr, "pirate_bay_native: fd %d closed, exiting\n", in.fd);
      exit(0);
    }
    if (in.len < 0) {
      in.len = 0;
      return -1;
    }
  }
  return in.buf[in.pos++];
}

bool readable(int fd) {
  struct pollfd p = {fd, POLLIN, 0};
  return poll(&p, 1, 0) > 0;
}

void write_all(int fd, const uint8_t *data, uint16_t n) {
  while (n) {
    ssize_t done = write(fd, data, n);
    if (done < 0) {
      if (errno == EINTR) continue;
      fprintf(stderr, "pirate_bay_native: write to fd %d failed, exiting\n", fd);
      exit(0);
    }
    data += done;
    n -= (uint16_t)done;
  }
}

}  // namespace

int hal_linux_bus_fd = 3;

namespace hal {

void begin() { bus_in.fd = hal_linux_bus_fd; }

uint32_t millis() {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (uint32_t)((uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u);
}

int link_read() {
  if (link_in.pos >= link_in.len && !readable(kLinkIn)) return -1;
  return next_byte(link_in);
}

void link_write(const uint8_t *data, uint16_t n) { write_all(kLinkOut, data, n); }

int bus_read() {
  if (bus_in.pos >= bus_in.len && !readable(bus_in.fd)) return -1;
  return next_byte(bus_in);
}

void bus_write(const uint8_t *data, uint16_t n) { write_all(bus_in.fd, data, n); }

void idle() {
  // Sleep until input arrives or 1 ms passes: the timers need ms resolution.
  struct pollfd p[2] = {{kLinkIn, POLLIN, 0}, {bus_in.fd, POLLIN, 0}};
  poll(p, 2, 1);
}

}  // namespace hal
