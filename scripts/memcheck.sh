#!/usr/bin/env bash
# valgrind memcheck over the lifecycle of every packaged FMU (dist/*.fmu,
# dist/fmi3/*.fmu and dist/fmi3-scalar/*.fmu, built by scripts/build-fmus.sh): load,
# instantiate, initialize, steps, FMU states, reset, free, unload, through the FMI 2.0
# interface (Model Exchange, Co-Simulation) and the FMI 3.0 interface (Model Exchange,
# Co-Simulation with and without event mode, partial derivatives, variable
# dependencies), the latter twice: the array view and the scalar-only view (the same
# binary, instantiated with the scalar token). Then the issue 20 probes
# (robofmu-hostile-reentry): loggers that free, reset, set states and re-enter, reused
# handles, a second thread on a busy instance, forged states, both standards, every
# FMU; and the C and C++ hosts that leave the logger with longjmp (tests/leave.rs in
# crates/test/hostile). Fails on any memcheck error and on any definite leak. Installs
# valgrind from Debian when it is missing and this runs as root (CI); otherwise asks
# for it.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v valgrind >/dev/null 2>&1; then
    if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1; then
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq valgrind >/dev/null
    else
        echo "valgrind is missing: install it (Debian: apt-get install valgrind)" >&2
        exit 1
    fi
fi
cargo build --release -p robofmu-hostile --bin robofmu-hostile-lifecycle \
    --bin robofmu-hostile-reentry
for program in robofmu-hostile-lifecycle robofmu-hostile-reentry; do
    valgrind --error-exitcode=1 --errors-for-leak-kinds=definite --leak-check=full \
        --show-leak-kinds=definite -q "target/release/$program"
done
# Hosts that leave the logger with longjmp (issue 42): the instance freed, no leak.
ROBOFMU_LEAVE_VALGRIND=1 cargo test --release -p robofmu-hostile --test leave
