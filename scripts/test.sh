#!/usr/bin/env bash
# The whole test suite: formatting, lints, rustdoc, Rust tests, FMU tests. Run from anywhere.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo fmt --all -- --check
cargo clippy --workspace --all-targets -- -D warnings
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --workspace
# dist/*.fmu first: the hostile importer's tests (crates/test/hostile) dlopen the packaged
# binaries and fail when they are missing or older than the sources. It builds the FMUs
# for all five platforms (a platform it cannot build is named, and skipped with that
# reason by tests/python/test_platforms.py).
bash scripts/build-fmus.sh
cargo test --workspace --release
# valgrind memcheck over each FMU's lifecycle (installs valgrind in CI).
bash scripts/memcheck.sh
# libtbb12 for ecospy (installed with apt-get in CI, as valgrind is).
bash scripts/install-importer-libs.sh
# Wine, qemu-aarch64 and llvm-tools for tests/python/test_platforms.py (apt-get and
# rustup in CI): the Windows and aarch64 Linux binaries run there, the macOS ones are
# read statically.
bash scripts/install-platform-test-tools.sh
# Debian's chromium for tests/python/test_verify_page.py (apt-get in CI): the results page
# of `cosim verify TREE --html` opened headless, its images loaded, a screenshot kept.
bash scripts/install-browser.sh
# FMUs through a real importer: create the pinned venv, run pytest
# (pytest exits 5 when it collects nothing; that counts as a failure too).
bash scripts/setup-venv.sh
# gemseo-fmu in a venv of its own (it pins an older FMPy) for tests/python/test_gemseo_fmu.py.
bash scripts/setup-gemseo-venv.sh
# The harness's lint and types (configured in pyproject.toml): zero findings.
.venv/bin/ruff check robofmu tests/wheel scripts/api_docs.py examples/robofmu.ipynb
.venv/bin/mypy
# The public API (robofmu/__init__.py, api.py, errors.py, instances.py) under mypy --strict
# (the modules it imports are read, their findings left to the run above); its reference:
# pdoc (pinned) renders the docstrings of robofmu.__all__ into target/api-docs, failing on
# any warning.
.venv/bin/mypy --strict --follow-imports=silent robofmu/__init__.py robofmu/api.py \
    robofmu/errors.py robofmu/instances.py
.venv/bin/python scripts/api_docs.py target/api-docs
.venv/bin/python -m pytest tests/python -q
# The wheel as a user installs it: built, installed into a fresh venv in an empty folder
# (no checkout, no Rust on PATH), a bundled scenario and a bundled `cosim verify` case run
# there; cosim --version = Cargo.toml's version = every FMU's (about a minute, mostly pip).
bash scripts/test-wheel.sh
