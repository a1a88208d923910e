# The two commands of the README: `make demo` and `make test`.
# Both create .venv (with the `test` extra: ROS 2 wheels, colcon, test tools) on first
# use; only Python 3.11, pip and make are needed.

# The ROS 2 wheels on the Python registry are built for CPython 3.11 only.
ROS_WHEELS_PYTHON := 3.11
comma := ,
PYTHON ?= $(shell command -v python$(ROS_WHEELS_PYTHON) 2>/dev/null || command -v python3)
VENV ?= .venv
BIN := $(VENV)/bin
DEPS := $(VENV)/.deps
STAMP := $(VENV)/.installed
CONSTRAINTS := constraints.txt
# The project is installed for real (not editable: editable installs skip the CMake
# files that `find_package(ament_nodl)` needs), and reinstalled when a source changes.
SOURCES := $(shell find nodl nodl_schema ros -type f -not -name '*.pyc' -not -path '*/node_modules/*' \
             -not -path 'nodl/studio/static/vendor/*') pyproject.toml
# nodl studio's browser libraries (Cytoscape.js, cytoscape-edgehandles): installed from the npm
# registry at the versions of their lock, then copied where the package serves them from.
STUDIO_WEB := nodl/studio/web
STUDIO_VENDOR := nodl/studio/static/vendor/.copied

# Anything that starts ROS stays on loopback, in its own domain.
export ROS_AUTOMATIC_DISCOVERY_RANGE := LOCALHOST
export ROS_DOMAIN_ID ?= 57
# The ROS 2 wheels install an ament prefix into the virtual environment.
export AMENT_PREFIX_PATH := $(abspath $(VENV))
export CMAKE_PREFIX_PATH := $(abspath $(VENV))
export PATH := $(abspath $(BIN)):$(PATH)

.PHONY: demo test bench docs install lock system-deps clean FORCE

install: $(STAMP)

# A .venv made by another interpreter (another Python version, or one since removed)
# cannot load the ROS 2 wheels: it is rebuilt, saying why.
VENV_MADE_WITH := $(shell sed -n 's/^version\(_info\)\{0,1\} *= *\([0-9]*\.[0-9]*\).*/\2/p' $(VENV)/pyvenv.cfg 2>/dev/null | head -n 1)
ifneq ($(wildcard $(VENV)/pyvenv.cfg),)
ifneq ($(VENV_MADE_WITH)-$(shell $(BIN)/python -S -c 'print(1)' 2>/dev/null),$(ROS_WHEELS_PYTHON)-1)
STALE_VENV := yes
endif
endif

$(DEPS): pyproject.toml $(CONSTRAINTS) tools/lock.in $(if $(STALE_VENV),FORCE)
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info[:2] != ($(subst .,$(comma),$(ROS_WHEELS_PYTHON))))' 2>/dev/null || { \
	  echo "make: '$(PYTHON)' is not Python $(ROS_WHEELS_PYTHON), which the ROS 2 wheels need."; \
	  echo "      Install python$(ROS_WHEELS_PYTHON), or run: make PYTHON=/path/to/python$(ROS_WHEELS_PYTHON) $(MAKECMDGOALS)"; \
	  echo "      (With a system ROS instead, see the docs: ros/nodl_toolkit/doc/guides/getting-started.md, Set-ups.)"; exit 2; }
	@if [ -n "$(STALE_VENV)" ]; then \
	  echo "make: $(VENV) was made with Python $(or $(VENV_MADE_WITH),?) or its interpreter is gone; rebuilding it with $(PYTHON)"; \
	  rm -rf $(VENV); fi
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	@echo "Installing the dependencies into $(VENV) (the first time: about 100 packages, ROS 2 included)"
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --upgrade pip setuptools wheel -c $(CONSTRAINTS)
	$(BIN)/python tools/pip_install.py -c $(CONSTRAINTS) '.[test]' -r tools/lock.in
	touch $(DEPS)

FORCE:

$(STUDIO_VENDOR): $(DEPS) $(STUDIO_WEB)/package.json $(STUDIO_WEB)/package-lock.json nodl/studio/vendor.py nodl/cli/verbs/studio.py
	@command -v npm >/dev/null 2>&1 || { echo "make: nodl studio needs npm (Node.js) to install its browser libraries: apt-get install npm"; exit 2; }
	npm ci --prefix $(STUDIO_WEB) --no-audit --no-fund --loglevel=error
	$(BIN)/python -c 'import sys; from nodl.cli.verbs.studio import copy_vendor_main; sys.exit(copy_vendor_main())' $(STUDIO_WEB)/node_modules
	touch $@

$(STAMP): $(DEPS) $(SOURCES) $(STUDIO_VENDOR)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps --no-build-isolation --force-reinstall .
	touch $(STAMP)

# What the suite needs from the system besides Python: a browser for the graph page's
# tests (Debian's chromium and its driver). Installed with apt-get when missing and run
# as root; otherwise it says what to install.
SYSTEM_PACKAGES := chromium chromium-driver
system-deps:
	@missing=""; command -v chromium >/dev/null 2>&1 || missing="chromium"; \
	  command -v chromedriver >/dev/null 2>&1 || missing="$$missing chromium-driver"; \
	  if [ -z "$$missing" ]; then exit 0; fi; \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "make: installing $$missing (Debian packages the test suite needs)"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(SYSTEM_PACKAGES); \
	  else \
	    echo "make: the test suite needs the Debian packages $(SYSTEM_PACKAGES): sudo apt-get install $(SYSTEM_PACKAGES)"; exit 2; \
	  fi

demo: $(STAMP)
	$(BIN)/python examples/demo.py

# The suite runs on as many workers as the machine has cores. Each worker gets whole
# modules (their module-scoped builds and nodes are made once), the costliest first
# (tests/durations.json; see tests/conftest.py), and a ROS domain of its own.
TEST_WORKERS ?= $(shell nproc 2>/dev/null || echo 2)
test: system-deps $(STAMP)
	$(BIN)/python -m pytest -n $(TEST_WORKERS) --dist loadfile --no-loadscope-reorder

# The lock, constraints.txt: every package of the environment pinned with ==. It is
# regenerated only on purpose: `make lock` keeps the pinned versions and resolves what
# pyproject.toml or tools/lock.in added; `make lock UPGRADE=1` moves everything to the
# newest versions pyproject.toml admits. Run `make test` on the result before committing.
lock: $(DEPS)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check uv -c $(CONSTRAINTS)
	$(BIN)/python tools/lock.py $(if $(UPGRADE),--upgrade)

bench: $(STAMP)
	$(BIN)/python bench/run.py

# The documentation site (ros/nodl_toolkit/doc, which rosdoc2 also builds for nodl_toolkit),
# warnings as errors, into build/docs (open build/docs/index.html). Built from a copy in
# build/docs-src: the build writes the examples' node pages into its source folder.
docs: $(DEPS)
	rm -rf build/docs-src && mkdir -p build && cp -R ros/nodl_toolkit/doc build/docs-src
	$(BIN)/python -m sphinx -W --keep-going -b html build/docs-src build/docs

clean:
	rm -rf $(VENV) build install log *.egg-info
