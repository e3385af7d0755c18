#!/usr/bin/env bash
# The main demo: builds the FMUs, creates the Python environment, runs the six PID
# scenarios of robofmu.demo.SCENARIOS (planner -> PID -> 3-PSS plant, each also under
# computed torque) through FMPy, and writes the
# result CSVs and PNG plots to results/ with a summary table on the terminal; then a
# small sweep on a Dask LocalCluster (sweeps/demo_gains.toml: 15 runs) with its table
# and plots in results/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build-fmus.sh
bash scripts/setup-venv.sh
.venv/bin/cosim demo --out results "$@"
.venv/bin/cosim sweep sweeps/demo_gains.toml --out results
