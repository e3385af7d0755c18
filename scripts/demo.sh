#!/usr/bin/env bash
# The main demo: builds the FMUs, creates the Python environment, runs every
# closed-loop scenario (planner -> PID -> 3-PSS plant) through FMPy, and writes the
# result CSVs and PNG plots to results/ with a summary table on the terminal.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build-fmus.sh
bash scripts/setup-venv.sh
.venv/bin/python -m cosim.demo --out results "$@"
