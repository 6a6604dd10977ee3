# Two commands for a fresh Debian 12 machine: `make demo` and `make test`.
# Both install the system packages they need when missing (needs root or sudo).

APT_PACKAGES := libmujoco-dev libosmesa6-dev
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
CARGO ?= cargo

PYTHON ?= python3
# The Python package's virtual environment (git-ignored, under target/).
PY_VENV := target/py-venv
# The binaries (cosco, simulate) the Python tests and the docs' commands run, in target/debug:
# built as `cargo test` builds them for the command-line tests (the crate with the test build's
# features), so that after `cargo test --all-targets` nothing is compiled again (`cargo build
# --bins` would compile the crate once more, with a plain build's features)
TEST_BINS := $(CARGO) test --no-run --test cli

.PHONY: deps demo test structure test-python doc-commands results bench bench-som bindings fmt clippy clean

## deps: install the Debian packages (MuJoCo 2.2.2, OSMesa) when any is missing
deps:
	@missing=""; for p in $(APT_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  $(SUDO) apt-get update && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y --no-install-recommends $$missing; \
	else echo "system packages present: $(APT_PACKAGES)"; fi

## demo: build in release mode and run the main job (writes out/)
demo: deps
	$(CARGO) build --release --bins
	$(CARGO) run --release --bin simulate -- --out out

## test: the whole test suite, headless: with the simulator (default); without it (the
## algorithm alone, as the Python package builds it: the binaries' and the command line's
## tests, and the doctests; the library's unit tests are the same code as above, and
## `make clippy` compiles every target in both feature sets); then the Python package's tests
## and the docs' commands
test: deps structure
	$(CARGO) test --all-targets
	$(CARGO) test --doc
	$(CARGO) test --no-default-features --bins --test cli
	$(CARGO) test --no-default-features --doc
	$(MAKE) test-python
	$(MAKE) doc-commands

## structure: no import circle among the files under src/, no file there over 800 lines
## (the generated bindings aside)
structure:
	@command -v $(PYTHON) >/dev/null 2>&1 || { $(SUDO) apt-get update && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y --no-install-recommends python3; }
	$(PYTHON) scripts/import_circles.py src
	@if $(PYTHON) scripts/import_circles.py tests/fixtures/import-circle >/dev/null; then \
	  echo "scripts/import_circles.py missed the circle of tests/fixtures/import-circle"; exit 1; fi
	@big=$$(find src -name '*.rs' ! -name ffi.rs -exec wc -l {} + | awk '$$2 != "total" && $$1 > 800 {print "  " $$2 " (" $$1 " lines)"}'); \
	if [ -n "$$big" ]; then echo "files over 800 lines under src/:"; echo "$$big"; exit 1; else echo "no file under src/ over 800 lines"; fi

## test-python: build the Python package (python/, without the simulator; in the dev profile,
## as the tests above) into a local virtual environment and run its tests against the `cosco`
## binary the tests above use (TEST_BINS; the export round trips are read back by
## mcap-ros2-support); skipped when python3 is absent
test-python:
	@if ! command -v $(PYTHON) >/dev/null 2>&1; then echo "$(PYTHON) not found: Python tests skipped"; exit 0; fi; \
	set -e; \
	if [ ! -x $(PY_VENV)/bin/python ]; then \
	  $(PYTHON) -m venv $(PY_VENV) || { $(SUDO) apt-get install -y --no-install-recommends python3-venv && $(PYTHON) -m venv $(PY_VENV); }; \
	fi; \
	$(PY_VENV)/bin/pip install -q --disable-pip-version-check "maturin>=1.5,<2" pytest numpy "mcap-ros2-support>=0.5,<1" "movement_primitives==0.9.1" scipy pytransform3d; \
	$(TEST_BINS); \
	PATH="$(CURDIR)/$(PY_VENV)/bin:$$PATH" CARGO_TARGET_DIR=$(CURDIR)/target MATURIN_PEP517_ARGS="--profile dev" $(PY_VENV)/bin/pip install -q --disable-pip-version-check --no-build-isolation --force-reinstall --no-deps ./python; \
	COSCO_BIN=$(CURDIR)/target/debug/cosco $(PY_VENV)/bin/python -m pytest -q python/tests

## doc-commands: run every command block of README.md, CONTRIBUTING.md and docs/ as written,
## in a clean clone (blocks fenced ```sh long are skipped; Python blocks need test-python)
doc-commands:
	@command -v $(PYTHON) >/dev/null 2>&1 || { $(SUDO) apt-get update && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y --no-install-recommends python3; }
	$(TEST_BINS)
	$(PYTHON) scripts/doc_commands.py

## results: rerun every study and rewrite docs/RESULTS.md and README.md's headline table
results: deps
	scripts/results.sh

## bench: criterion benchmarks (figures go to docs/BENCHMARKS.md by hand)
bench: deps
	$(CARGO) bench

## bench-som: the SOM kernel against its roofline and MiniSom (venv in target/minisom-venv)
bench-som: deps
	CARGO=$(CARGO) benches/minisom.sh --plot docs/figures/som-step-vs-size.png

## bindings: regenerate src/mujoco/ffi.rs with bindgen (needs libclang-dev)
bindings:
	@dpkg-query -W -f='$${Status}' libclang-dev 2>/dev/null | grep -q "install ok installed" || \
	  ($(SUDO) apt-get update && $(SUDO) apt-get install -y libclang-dev)
	CARGO=$(CARGO) scripts/regen-bindings.sh

fmt:
	$(CARGO) fmt --all

## clippy: every target, with the simulator and without it
clippy:
	$(CARGO) clippy --all-targets -- -D warnings
	$(CARGO) clippy --no-default-features --all-targets -- -D warnings

clean:
	$(CARGO) clean
