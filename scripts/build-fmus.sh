#!/usr/bin/env bash
# Builds the FMU cdylibs in release mode and packages dist/<Model>.fmu
# (modelDescription.xml, binaries/linux64/<modelIdentifier>.so, documentation/).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --workspace
target/release/robofmu fmi package --libraries target/release --out dist
