# linkage-kinematics. `make help` lists the targets; README gives the two that matter.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
SOURCES := Cargo.toml pyproject.toml $(shell find crates python -name '*.rs' -o -name '*.py' -o -name '*.pyi' -o -name Cargo.toml)
FIRMWARE := thumbv7em-none-eabihf
DIST   := dist
# The declared minimum Rust (Cargo.toml's rust-version), checked by `make msrv`.
MSRV   := $(shell sed -n 's/^rust-version = "\(.*\)"/\1/p' Cargo.toml)

SIZE := $(shell command -v llvm-size || ls $$HOME/.rustup/toolchains/*/lib/rustlib/*/bin/llvm-size 2>/dev/null | head -n 1)

.PHONY: help run test check msrv wheel wheel-test firmware firmware-size bench fuzz clean

help: ## List the targets.
	@grep -E '^[a-z-]+:.*## ' $(MAKEFILE_LIST) | sed 's/:.*## /\t/' | expand -t 12

$(STAMP): $(SOURCES)
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test]"
	touch $@

run: $(STAMP) ## Set up (venv, build) and run the main job: `linkage run` (report in ./linkage-report/).
	$(BIN)/linkage run --force

# pytest's workers (pytest-xdist) for `make test` and the suite in `make wheel-test`; 0: one process.
PYTEST_WORKERS ?= 2

test: $(STAMP) ## Set up and run every test: Rust unit/property/doc tests, pytest + doctests, stubs, types (not the wheel: wheel-test).
	cargo test -p linkage-core --release
	$(BIN)/pytest tests python/linkage --ignore=tests/test_wheel.py $(if $(filter 0,$(PYTEST_WORKERS)),,-n $(PYTEST_WORKERS) --dist loadfile)
	$(BIN)/python -m mypy.stubtest linkage._core linkage._core.numeric linkage._core.drive linkage._core.mechanism linkage._core.motion linkage._core.sweep linkage._core.linkages linkage._core.kinetostatics linkage._core.catalog linkage._core.walking linkage._core.synthesis
	$(BIN)/mypy

check: $(STAMP) firmware firmware-size ## Formatting, lints (clippy -D warnings, ruff), rustdoc -D warnings, firmware builds.
	cargo fmt --all --check
	cargo clippy --workspace --all-targets -- -D warnings
	$(BIN)/python .ci/assert_messages.py
	$(BIN)/python .ci/layers.py
	$(BIN)/python .ci/long_functions.py
	$(BIN)/pytest -q -p no:cacheprovider tests/test_imports.py
	RUSTDOCFLAGS="-D warnings" cargo doc --no-deps -p linkage-core
	$(BIN)/ruff check python tests bench
	$(BIN)/ruff format --check python tests bench

msrv: ## Check the workspace and the no_std core with the minimum Rust (Cargo.toml rust-version; installs it).
	rustup toolchain install $(MSRV) --profile minimal
	CARGO_TARGET_DIR=target/msrv cargo +$(MSRV) check --workspace --all-targets --locked
	CARGO_TARGET_DIR=target/msrv cargo +$(MSRV) check -p linkage-core --no-default-features --features libm --locked

wheel: $(STAMP) ## Build the shipped wheel (abi3, manylinux2014 via zig, stripped, audited) and the sdist into dist/.
	$(BIN)/python -m pip install --quiet --group ship
	rm -f $(DIST)/linkage_kinematics-*.whl $(DIST)/linkage_kinematics-*.tar.gz
	PATH="$(abspath $(BIN)):$$PATH" $(BIN)/maturin build --sdist --locked --zig \
		--compatibility manylinux2014 --auditwheel check --out $(DIST)
	$(BIN)/auditwheel show $(DIST)/linkage_kinematics-*.whl
	@ls -l $(DIST)/linkage_kinematics-*

wheel-test: wheel ## Install the wheel into a fresh venv of each declared Python (3.9-3.13); run it and the whole pytest suite outside the tree.
	LINKAGE_WHEEL_DIST="$(CURDIR)/$(DIST)" LINKAGE_TEST_WORKERS=$(PYTEST_WORKERS) $(BIN)/pytest tests/test_wheel.py -p no:cacheprovider \
		-raP --durations=0 --durations-min=5

firmware: ## Build the core and a firmware example (f32 + f64) for thumbv7em-none-eabihf: no std, no heap.
	rustup target add $(FIRMWARE)
	cargo build -p linkage-core --no-default-features --features libm --target $(FIRMWARE)
	cargo build -p linkage-core --example firmware --no-default-features --features libm --target $(FIRMWARE) --release

firmware-size: ## Link a minimal Cortex-M4F image that solves and sweeps a four-bar (f32, f64); print its size.
	rustup target add $(FIRMWARE)
	cd bench/firmware-size && cargo build --release --quiet
	$(if $(SIZE),$(SIZE) bench/firmware-size/target/$(FIRMWARE)/release/firmware-size,@echo "(llvm-size not found: size not printed)")
	cd bench/firmware-size && cargo build --release --quiet --features double
	$(if $(SIZE),$(SIZE) bench/firmware-size/target/$(FIRMWARE)/release/firmware-size,@echo "(llvm-size not found: size not printed)")

bench: $(STAMP) ## Work-precision benchmark (mpmath, numpy, pylinkage, four-bar crate), stability report, firmware size.
	$(BIN)/python -m pip install --quiet "pylinkage>=1.3"
	$(BIN)/python bench/work_precision.py
	$(BIN)/python bench/stability.py
	$(MAKE) firmware-size

fuzz: $(STAMP) ## Long fuzzing runs: 1e5 proptest cases per property; ~2e5 hypothesis examples over the whole Python API.
	LINKAGE_PROPTEST_CASES=100000 cargo test -p linkage-core --release --test properties --test centres
	LINKAGE_FUZZ_EXAMPLES=20000 $(BIN)/pytest tests/test_fuzz.py -q
	LINKAGE_FUZZ_EXAMPLES=4000 $(BIN)/pytest tests/test_fuzz_api.py tests/test_memory_limits.py -q

clean: ## Remove the venv and build products.
	rm -rf $(VENV) target python/linkage/_core*.so $(DIST)/linkage_kinematics-*
