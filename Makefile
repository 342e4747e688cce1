# The two README commands: `make demo` and `make test`. Both create .venv on first use.
PY ?= python3
VENV := .venv
BIN := $(VENV)/bin

.PHONY: setup demo test lint bench clean

$(BIN)/teleo: pyproject.toml
	$(PY) -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip
	$(BIN)/pip install -q -e '.[dev]'
	touch $(BIN)/teleo

setup: $(BIN)/teleo

demo: setup
	$(BIN)/teleo launch scenarios/driving_demo.toml --summary out/demo-summary.json --render out/demo.png

test: setup
	$(BIN)/ruff check .
	$(BIN)/python -m pytest -q

bench: setup
	$(BIN)/python bench/engine.py
	$(BIN)/python bench/bus.py
	$(BIN)/python bench/world.py
	$(BIN)/python bench/cycle.py

clean:
	rm -rf $(VENV) out .pytest_cache
