#!/usr/bin/env bash
# The whole test suite: formatting, lints, rustdoc, Rust tests, FMU tests. Run from anywhere.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo fmt --all -- --check
cargo clippy --workspace --all-targets -- -D warnings
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --workspace
cargo test --workspace --release
# FMUs through a real importer: build dist/*.fmu, create the pinned venv, run pytest
# (pytest exits 5 when it collects nothing; that counts as a failure too).
bash scripts/build-fmus.sh
bash scripts/setup-venv.sh
.venv/bin/python -m pytest tests/python -q
