# The two README commands: `make demo` and `make test`. Both create .venv on first use.
PY ?= python3
VENV := .venv
BIN := $(VENV)/bin

.PHONY: setup browser demo test lint bench clean netns-tools

$(BIN)/teleo: pyproject.toml
	$(PY) -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip
	$(BIN)/pip install -q -e '.[dev]'
	touch $(BIN)/teleo

setup: $(BIN)/teleo netns-tools

# The cross-host test (tests/e2e/test_hosts_live.py) joins two Linux network namespaces with
# a veth pair, which needs root and iproute2's `ip`; install it where we can (Debian, root).
netns-tools:
	@command -v ip >/dev/null 2>&1 || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1 \
		&& apt-get update -qq && apt-get install -y -qq iproute2 >/dev/null; } \
		|| echo "note: no iproute2 (ip) or not root: the cross-host test will be skipped"

# Headless Chromium for the web view's browser test (tests/e2e/test_view_browser.py), from
# Debian's packages when it is missing (CI runs as root; elsewhere run this once with sudo).
browser:
	@command -v chromium >/dev/null 2>&1 || { \
	  echo "installing chromium (apt-get) for the browser test"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; }

demo: setup
	$(BIN)/teleo launch scenarios/driving_demo.toml --summary out/demo-summary.json --render out/demo.png

test: setup browser
	$(BIN)/ruff check .
	$(BIN)/python -m pytest -q

bench: setup
	$(BIN)/python bench/speed/engine.py
	$(BIN)/python bench/speed/bus.py
	$(BIN)/python bench/speed/world.py
	$(BIN)/python bench/speed/cycle.py

clean:
	rm -rf $(VENV) out .pytest_cache
