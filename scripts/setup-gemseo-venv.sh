#!/usr/bin/env bash
# Creates (or reuses) .venv-gemseo at the repository root with gemseo-fmu 3.1.1 and its
# dependencies, pinned in scripts/gemseo-requirements.txt, for tests/python/test_gemseo_fmu.py
# (which runs tests/python/gemseo_runs.py there). A venv of its own: gemseo-fmu requires
# FMPy <= 0.3.19, the main venv (scripts/setup-venv.sh) pins FMPy 0.3.32. About 1.1 GB
# installed (gemseo[all]: openturns, scipy, pandas, scikit-learn, sympy, plotly): 95 s
# from a warm pip cache on the loaded 2-core machine with --no-compile (Python compiles
# what it imports; byte-compiling everything took 424 s). Idempotent: a second run only
# compares the pins.
set -euo pipefail
cd "$(dirname "$0")/.."

requirements=scripts/gemseo-requirements.txt
venv=.venv-gemseo
stamp="$venv/.requirements-installed"

if [[ ! -x "$venv/bin/python" ]]; then
    python3 -m venv "$venv"
fi
if ! { [[ -f "$stamp" ]] && cmp -s "$requirements" "$stamp"; }; then
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-compile \
        -r "$requirements"
    cp "$requirements" "$stamp"
fi
