#!/usr/bin/env bash
# Creates (or reuses) the Python virtual environment .venv at the repository root with
# the pinned packages the FMU tests need. Idempotent: a second run only checks the pins.
set -euo pipefail
cd "$(dirname "$0")/.."

requirements=scripts/python-requirements.txt
venv=.venv
stamp="$venv/.requirements-installed"

if [[ ! -x "$venv/bin/python" ]]; then
    python3 -m venv "$venv"
fi
if [[ -f "$stamp" ]] && cmp -s "$requirements" "$stamp"; then
    exit 0
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements"
cp "$requirements" "$stamp"
