#!/usr/bin/env bash
# Runs tests/python in two pytest processes at once: the test files named as arguments,
# in one process in their order, and every other test file in the second. Prints the
# two logs one after the other and fails when either run fails (pytest exits 5 when it
# collects nothing: a failure too).
#
# Usage: bash scripts/pytest-two.sh FILE...
set -uo pipefail
# Job control: without it bash starts background commands with SIGINT ignored, and the
# tests that interrupt a command as a terminal's Ctrl-C does would find it ignored too.
set -m
cd "$(dirname "$0")/.."
[[ $# -gt 0 ]] || { echo "pytest-two.sh: name the test files of the first process" >&2; exit 2; }
logs=$(mktemp -d)
first="" second=""
trap 'kill $first $second 2>/dev/null; rm -rf "$logs"' EXIT
ignored=()
for file in "$@"; do
    [[ -f "$file" ]] || { echo "pytest-two.sh: $file: no such test file" >&2; exit 2; }
    ignored+=("--ignore=$file")
done
.venv/bin/python -m pytest -p no:cacheprovider -q "$@" >"$logs/first" 2>&1 &
first=$!
.venv/bin/python -m pytest -p no:cacheprovider -q tests/python "${ignored[@]}" >"$logs/second" 2>&1 &
second=$!
wait "$first"
first_status=$?
wait "$second"
second_status=$?
echo "== pytest $* (exit $first_status)"
cat "$logs/first"
echo "== pytest, every other test file (exit $second_status)"
cat "$logs/second"
[[ $first_status -eq 0 && $second_status -eq 0 ]]
