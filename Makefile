# Two commands on a fresh clone (needs only Python 3.11 and make):
#   make demo   create .venv, install the package, build the default template into out/
#   make test   install the test extras into .venv, run the lint and the whole test suite
PYTHON ?= $(shell command -v python3.11 2>/dev/null || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
TEMPLATE ?= templates/patkau-one-fold.toml
OUT ?= out

.PHONY: demo test lint api clean programs

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $@ $(VENV)/.installed

demo: $(VENV)/.installed
	$(BIN)/onefold build $(TEMPLATE) -o $(OUT)

# The README's test command: the lint first (ruff, layers, mypy), then every test.
test: $(VENV)/.installed-test programs lint
	$(BIN)/python -m pytest -n auto

# Debian programs the tests drive: Chromium with playwright (tests/explore/),
# CalculiX's ccx, which runs the NAME.inp simulate writes, and ParaView's
# pvpython, which reads its NAME.vtu (tests/export/), and FreeCAD's freecadcmd,
# which weighs the STEP solid (tests/export/test_aligned_plane.py).
# As root, install those missing; otherwise stop with the one command to run.
PROGRAMS := /usr/bin/chromium:chromium /usr/bin/ccx:calculix-ccx /usr/bin/pvpython:python3-paraview \
  /usr/bin/freecadcmd:freecad-python3
programs:
	@missing=""; for p in $(PROGRAMS); do \
	  [ -x "$${p%%:*}" ] || missing="$$missing $${p#*:}"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "installing Debian's$$missing for the tests"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing >/dev/null; \
	  else \
	    echo "make test needs$$missing for its tests; run:  sudo apt-get install -y$$missing" >&2; \
	    exit 1; \
	  fi; \
	fi

# ruff, the layer contract of pyproject.toml ([tool.importlinter]), then the
# types (mypy, configured in pyproject.toml's [tool.mypy]: zero errors).
lint: $(VENV)/.installed-test
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	$(BIN)/lint-imports
	$(BIN)/mypy onefold_cad

# The API reference (pdoc, from the docstrings) into docs/api/, a build folder.
api: $(VENV)/.installed-test
	$(BIN)/python docs/make_reference.py --api docs/api

clean:
	rm -rf $(OUT) build *.egg-info .pytest_cache .ruff_cache
