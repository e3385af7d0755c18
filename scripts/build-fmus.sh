#!/usr/bin/env bash
# Builds the FMU cdylibs in release mode and packages dist/<Model>.fmu
# (modelDescription.xml, binaries/linux64/<modelIdentifier>.so, documentation/).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -p robofmu-planner-fmu -p robofmu-pid-fmu -p robofmu --bin robofmu
target/release/robofmu fmi package --libraries target/release --out dist
