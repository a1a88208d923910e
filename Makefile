# The two commands of the README: `make demo` and `make test`.
# Both create .venv (with every extra) on first use; only Python, pip and make are needed.

PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

# Anything that starts ROS stays on loopback, in its own domain.
export ROS_AUTOMATIC_DISCOVERY_RANGE := LOCALHOST
export ROS_DOMAIN_ID ?= 57
# The ROS 2 wheels install an ament prefix into the virtual environment.
export AMENT_PREFIX_PATH := $(abspath $(VENV))
export CMAKE_PREFIX_PATH := $(abspath $(VENV))

.PHONY: demo test bench install clean

install: $(STAMP)

$(STAMP): pyproject.toml setup.py
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[ros,test]'
	# An editable install is not byte-compiled by pip; compile it so `nodl` starts fast
	# even where PYTHONDONTWRITEBYTECODE is set.
	$(BIN)/python -m compileall -q nodl_schema
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/python examples/demo.py

test: $(STAMP)
	$(BIN)/python -m pytest

bench: $(STAMP)
	$(BIN)/python bench/run.py

clean:
	rm -rf $(VENV) build install log *.egg-info
