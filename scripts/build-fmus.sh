#!/usr/bin/env bash
# Builds every FMU crate under fmus/ in release mode and packages dist/<Model>.fmu
# (FMI 2.0) and dist/fmi3/<Model>.fmu (FMI 3.0, same cdylib)
# (modelDescription.xml, binaries/<platform>/<modelIdentifier>.<ext>,
# documentation/). Each FMU crate's example `<package>-package` is its packager (an
# example, so that the packaging crates stay out of the cdylib's dependencies): it finds
# the cdylib cargo built, so adding an FMU needs no change here.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=()
for manifest in fmus/*/Cargo.toml; do
    packages+=("$(sed -n 's/^name = "\(.*\)"$/\1/p' "$manifest" | head -n 1)")
done
cargo build --release --workspace
cargo build --release --workspace --examples
for package in "${packages[@]}"; do
    "target/release/examples/$package-package" package --out dist
done
