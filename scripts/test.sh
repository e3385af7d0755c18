#!/usr/bin/env bash
# The whole test suite: formatting, lints, rustdoc, Rust tests, FMU tests. Run from anywhere.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each step prints its wall time to stderr, so that CI's log shows where its minutes go.
step() {
    local start=$SECONDS
    "$@"
    echo "test.sh: $((SECONDS - start)) s for: $*" >&2
}
step cargo fmt --all -- --check
step cargo clippy --workspace --all-targets -- -D warnings
step env RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --workspace
# dist/*.fmu first: the hostile importer's tests (crates/test/hostile) dlopen the packaged
# binaries and fail when they are missing or older than the sources. It builds the FMUs
# for all five platforms (a platform it cannot build is named, and skipped with that
# reason by tests/python/test_platforms.py).
step bash scripts/build-fmus.sh
step cargo test --workspace --release
# valgrind memcheck over each FMU's lifecycle (installs valgrind in CI).
step bash scripts/memcheck.sh
# libtbb12 for ecospy (installed with apt-get in CI, as valgrind is).
step bash scripts/install-importer-libs.sh
# Wine, qemu-aarch64 and llvm-tools for tests/python/test_platforms.py (apt-get and
# rustup in CI): the Windows and aarch64 Linux binaries run there, the macOS ones are
# read statically.
step bash scripts/install-platform-test-tools.sh
# Debian's chromium for tests/python/test_verify_page.py (apt-get in CI): the results page
# of `cosim verify TREE --html` opened headless, its images loaded, a screenshot kept.
step bash scripts/install-browser.sh
# FMUs through a real importer: create the pinned venv, run pytest
# (pytest exits 5 when it collects nothing; that counts as a failure too).
step bash scripts/setup-venv.sh
# gemseo-fmu in a venv of its own (it pins an older FMPy) for tests/python/test_gemseo_fmu.py.
step bash scripts/setup-gemseo-venv.sh
# The harness's lint and types (configured in pyproject.toml): zero findings.
step .venv/bin/ruff check robofmu tests/wheel scripts/api_docs.py examples/robofmu.ipynb
step .venv/bin/mypy
# The public API (robofmu/__init__.py, api.py, errors.py, instances.py) under mypy --strict
# (the modules it imports are read, their findings left to the run above); its reference:
# pdoc (pinned) renders the docstrings of robofmu.__all__ into target/api-docs, failing on
# any warning.
step .venv/bin/mypy --strict --follow-imports=silent robofmu/__init__.py robofmu/api.py \
    robofmu/errors.py robofmu/instances.py
step .venv/bin/python scripts/api_docs.py target/api-docs
# Two pytest processes at once (CI has 2 cores): one runs, in order, the tests that run
# commands in the repository and check what each wrote (the documented commands, the
# release script: they rebuild dist/ and watch the tree), the other every other test
# (none writes in the tree outside results/). Each writes its own log, shown after both.
step bash scripts/pytest-two.sh tests/python/test_documented_commands.py tests/python/test_release.py
# The wheel as a user installs it: built, installed into a fresh venv in an empty folder
# (no checkout, no Rust on PATH), a bundled scenario and a bundled `cosim verify` case run
# there; cosim --version = Cargo.toml's version = every FMU's (about a minute, mostly pip).
step bash scripts/test-wheel.sh
echo "test.sh: $SECONDS s in all" >&2
