#!/usr/bin/env bash
# The whole test suite: formatting, lints, Rust tests. Run from anywhere.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo fmt --all -- --check
cargo clippy --workspace --all-targets -- -D warnings
cargo test --workspace --release
