# The two commands of the README: `make demo` and `make test`.
# Both create .venv (with every extra) on first use; only Python, pip and make are needed.

PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
DEPS := $(VENV)/.deps
STAMP := $(VENV)/.installed
# The project is installed for real (not editable: editable installs skip the CMake
# files that `find_package(ament_nodl)` needs), and reinstalled when a source changes.
SOURCES := $(shell find nodl_schema cmake -type f -not -name '*.pyc') pyproject.toml setup.py package.xml

# Anything that starts ROS stays on loopback, in its own domain.
export ROS_AUTOMATIC_DISCOVERY_RANGE := LOCALHOST
export ROS_DOMAIN_ID ?= 57
# The ROS 2 wheels install an ament prefix into the virtual environment.
export AMENT_PREFIX_PATH := $(abspath $(VENV))
export CMAKE_PREFIX_PATH := $(abspath $(VENV))
export PATH := $(abspath $(BIN)):$(PATH)

.PHONY: demo test bench install clean

install: $(STAMP)

$(DEPS): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip 'setuptools>=77,<80' wheel
	$(BIN)/python -m pip install --quiet '.[ros,test]'
	touch $(DEPS)

$(STAMP): $(DEPS) $(SOURCES)
	$(BIN)/python -m pip install --quiet --no-deps --no-build-isolation --force-reinstall .
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/python examples/demo.py

test: $(STAMP)
	$(BIN)/python -m pytest

bench: $(STAMP)
	$(BIN)/python bench/run.py

clean:
	rm -rf $(VENV) build install log *.egg-info
