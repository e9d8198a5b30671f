# linkage-kinematics. `make help` lists the targets; README gives the two that matter.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
SOURCES := Cargo.toml pyproject.toml $(shell find crates python -name '*.rs' -o -name '*.py' -o -name '*.pyi' -o -name Cargo.toml)
FIRMWARE := thumbv7em-none-eabihf

.PHONY: help run test check firmware clean

help: ## List the targets.
	@grep -E '^[a-z-]+:.*## ' $(MAKEFILE_LIST) | sed 's/:.*## /\t/' | expand -t 12

$(STAMP): $(SOURCES)
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test]"
	touch $@

run: $(STAMP) ## Set up (venv, build) and run the main job: `linkage run` (report in ./linkage-report/).
	$(BIN)/linkage run --force

test: $(STAMP) ## Set up and run every test: Rust unit/property/doc tests, pytest + doctests, stubs, types.
	cargo test -p linkage-core --release
	$(BIN)/pytest tests python/linkage
	$(BIN)/python -m mypy.stubtest linkage._core
	$(BIN)/mypy

check: $(STAMP) firmware ## Formatting, lints (clippy -D warnings, ruff) and the firmware build.
	cargo fmt --all --check
	cargo clippy --workspace --all-targets -- -D warnings
	$(BIN)/ruff check python tests
	$(BIN)/ruff format --check python tests

firmware: ## Build the core and a firmware example (f32 + f64) for thumbv7em-none-eabihf: no std, no heap.
	rustup target add $(FIRMWARE)
	cargo build -p linkage-core --no-default-features --features libm --target $(FIRMWARE)
	cargo build -p linkage-core --example firmware --no-default-features --features libm --target $(FIRMWARE) --release

clean: ## Remove the venv and build products.
	rm -rf $(VENV) target python/linkage/_core*.so
