"""Shared paths of the FMU tests: the FMUs come from dist/ (scripts/build-fmus.sh)."""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DIST = ROOT / "dist"
REFERENCES = ROOT / "tests" / "references"
# One FMU per checked-in modelDescription/<Model>.xml (the packager writes one for every
# FMU crate): adding an FMU changes no list here.
MODELS = sorted(path.stem for path in (ROOT / "modelDescription").glob("*.xml"))
INTERFACES = ["CoSimulation", "ModelExchange"]


def fmu_path(model):
    path = DIST / f"{model}.fmu"
    if not path.exists():
        pytest.fail(f"{path} is missing: run scripts/build-fmus.sh first")
    return str(path)


def fmu3_path(model):
    """The FMI 3.0 build of `model` (scripts/build-fmus.sh writes dist/fmi3/)."""
    path = DIST / "fmi3" / f"{model}.fmu"
    if not path.exists():
        pytest.fail(f"{path} is missing: run scripts/build-fmus.sh first")
    return str(path)
