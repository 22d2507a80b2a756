# arduino-mk settings for the Mega 2560, included by firmware/Makefile as
#   make -C PirateBay -f ../avr.mk
# Workarounds for Debian's arduino-mk 1.5.2 with the Debian arduino core:
# - every path given explicitly (its auto-detection looks for an IDE tree);
# - ARDUINO_VERSION set, or it guesses 1.0 and picks the wrong core layout;
# - BOARDS_TXT pointed at the avr architecture's boards.txt;
# - no libraries: the firmware is self-contained (ARDUINO_LIBS empty);
# - avr-gcc 5.4's float.h defines DECIMAL_DIG for C99 only, not C++11, and
#   the core's WString.cpp needs it: define it from the compiler's builtin.
# Debian 12: arduino-core-avr and gcc-avr. Ubuntu 20.04 has only the Arduino
# 1.0.5 core, without hardware/arduino/avr: there give the Arduino IDE 1.8.x
# folder, ARDUINO_DIR=~/arduino-1.8.19 AVR_TOOLS_DIR=~/arduino-1.8.19/hardware/tools/avr
# (doc/install.md); arduino-mk is Debian's or Ubuntu's either way.
ARDUINO_DIR     ?= /usr/share/arduino
ARDMK_DIR        = /usr/share/arduino
AVR_TOOLS_DIR   ?= /usr
ARDUINO_VERSION ?= 10819
ARCHITECTURE     = avr
BOARDS_TXT       = $(ARDUINO_DIR)/hardware/arduino/avr/boards.txt
ifeq ($(wildcard $(BOARDS_TXT)),)
$(error no $(BOARDS_TXT): install Debian 12's arduino-core-avr, or on Ubuntu 20.04 give the Arduino IDE 1.8.x folder as ARDUINO_DIR and its hardware/tools/avr as AVR_TOOLS_DIR (doc/install.md))
endif
BOARD_TAG        = mega
BOARD_SUB        = atmega2560
ARDUINO_LIBS     =
LINK_BAUD       ?= 57600
CPPFLAGS        += -DLINK_BAUD=$(LINK_BAUD)UL -DDECIMAL_DIG=__DECIMAL_DIG__
CXXFLAGS_STD     = -std=gnu++11
include /usr/share/arduino/Arduino.mk
