#!/usr/bin/env bash
# Builds the workspace in release mode and packages every FMU crate under fmus/ into
# dist/<Model>.fmu (FMI 2.0), dist/fmi3/<Model>.fmu (FMI 3.0) and
# dist/fmi3-scalar/<Model>.fmu (FMI 3.0, scalars only), all from the same cdylib
# (modelDescription.xml, binaries/<platform>/<modelIdentifier>.<ext>, documentation/).
# The workspace packager target/release/robofmu-packager (crates/packager) finds the
# FMU crates and reads each cdylib's description of itself, so adding an FMU needs no
# change here.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --workspace
target/release/robofmu-packager --out dist
