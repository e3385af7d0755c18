#!/usr/bin/env bash
# Creates (or reuses) the Python virtual environment .venv at the repository root with
# the pinned packages the FMU tests need, and installs this repository's harness into
# it (editable, no dependencies: .venv/bin/cosim runs robofmu/ from this checkout).
# Idempotent: a second run only checks the pins and the install.
set -euo pipefail
cd "$(dirname "$0")/.."

requirements=scripts/python-requirements.txt
venv=.venv
stamp="$venv/.requirements-installed"

if [[ ! -x "$venv/bin/python" ]]; then
    python3 -m venv "$venv"
fi
if ! { [[ -f "$stamp" ]] && cmp -s "$requirements" "$stamp"; }; then
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements"
    cp "$requirements" "$stamp"
fi
# The console script and the import path must point at this checkout (isolated mode: the
# current directory does not count).
# A checkout from before the package was renamed (cosim -> robofmu) keeps a console script
# that imports cosim: it is reinstalled too.
if [[ ! -x "$venv/bin/cosim" ]] || ! grep -q "from robofmu\.cli import" "$venv/bin/cosim" ||
    ! "$venv/bin/python" -I -c '
import pathlib, sys, robofmu
sys.exit(pathlib.Path(robofmu.__file__).resolve().parent.parent != pathlib.Path.cwd().resolve())
' 2>/dev/null; then
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-deps \
        --no-build-isolation --editable .
fi
