# PIRATE control stack. Two commands for a newcomer:
#   make demo   the stack against the simulated robot, headless
#   make test   every test (unit, rostest, firmware); non-zero on any failure
# Both install missing Debian packages and build the catkin workspace first.
SHELL := /bin/bash
# ROS lives in Debian's interpreter: /usr/bin first, always.
export PATH := /usr/bin:/bin:/usr/sbin:/sbin:$(PATH)
# Loopback unless the user chose otherwise (README "Running across machines").
export ROS_IP ?= 127.0.0.1
export ROS_HOSTNAME ?= 127.0.0.1
export PYTHONDONTWRITEBYTECODE := 1

WS ?= $(CURDIR)/.ws
ENV := source $(WS)/devel/setup.bash &&

.PHONY: deps build demo test test-unit test-rostest test-firmware lint bench clean

deps:
	@bash scripts/ensure_deps

$(WS)/src/pirate:
	@mkdir -p $(WS)/src
	@ln -sfn $(CURDIR) $(WS)/src/pirate

build: deps $(WS)/src/pirate
	@catkin_make -C $(WS) -DCATKIN_ENABLE_TESTING=1 -DPYTHON_EXECUTABLE=/usr/bin/python3 \
	  > $(WS)/build.log 2>&1 || { tail -40 $(WS)/build.log; exit 1; }
	@echo "built workspace $(WS)"

demo: build
	@$(ENV) bash scripts/demo

test: build
	@$(ENV) bash scripts/run_tests

test-unit: build
	@$(ENV) python3 -m pytest -q test/unit

test-rostest: build
	@$(ENV) bash scripts/run_rostests

lint: build
	@$(ENV) catkin_lint -W2 --strict .

bench: build
	@$(ENV) for b in bench/*; do [ -x "$$b" ] && "$$b"; done

clean:
	rm -rf $(WS) test-results
