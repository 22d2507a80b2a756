# PIRATE control stack. Two commands for a newcomer:
#   make demo   the stack against the simulated robot, headless
#   make test   every test (unit, rostest, firmware); non-zero on any failure
# Both install missing Debian packages and build the catkin workspace first.
SHELL := /bin/bash
# ROS lives in Debian's interpreter: /usr/bin first, always, after the
# project's virtual environment (.venv: Debian's python3 with its site
# packages plus MuJoCo from PyPI, made by scripts/ensure_deps).
VENV := $(CURDIR)/.venv
export PATH := $(VENV)/bin:/usr/bin:/bin:/usr/sbin:/sbin:$(PATH)
# Loopback unless the user chose otherwise (doc/interfaces.md "ROS networking").
export ROS_IP ?= 127.0.0.1
export ROS_HOSTNAME ?= 127.0.0.1
export PYTHONDONTWRITEBYTECODE := 1

WS ?= $(CURDIR)/.ws
ENV := source $(WS)/devel/setup.bash &&

.PHONY: deps link-package build demo test test-unit test-rostest test-firmware lint bench docs clean

deps:
	@bash scripts/ensure_deps

# The package in the workspace is a folder of links to the repo's top-level
# entries, not a link to the repo itself: the repo holds the workspace, and a
# link to it would make a loop that rosrun/find walk into.
link-package:
	@pkg=$(WS)/src/pirate; [ -L "$$pkg" ] && rm "$$pkg"; mkdir -p "$$pkg"; \
	  for f in $(CURDIR)/*; do ln -sfn "$$f" "$$pkg/$$(basename "$$f")"; done; \
	  for l in "$$pkg"/*; do [ -e "$$l" ] || rm -f "$$l"; done

build: deps link-package
	@catkin_make -C $(WS) -DCATKIN_ENABLE_TESTING=1 -DPYTHON_EXECUTABLE=$(VENV)/bin/python3 \
	  > $(WS)/build.log 2>&1 || { tail -40 $(WS)/build.log; exit 1; }
	@echo "built workspace $(WS)"

demo: build
	@$(ENV) bash scripts/demo

test: build
	@$(ENV) WS=$(WS) bash scripts/run_tests

test-unit: build
	@$(ENV) python3 -m pytest -q test/unit

test-rostest: build
	@$(ENV) bash scripts/run_rostests

# catkin_lint, flake8 (setup.cfg), yamllint (.yamllint) on config/, roslaunch-check.
lint: build
	@$(ENV) WS=$(WS) bash scripts/run_lint

# The tables in doc/ generated from the code (pirate.docs): rewrites them in place.
docs:
	@python3 scripts/make_docs

bench: build
	@$(ENV) for b in bench/*; do python3 "$$b" || exit 1; done

clean:
	rm -rf $(WS) test-results
