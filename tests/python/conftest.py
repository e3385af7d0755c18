"""Shared paths of the FMU tests: the FMUs come from dist/ (scripts/build-fmus.sh)."""

import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DIST = ROOT / "dist"
REFERENCES = ROOT / "tests" / "references"
# One FMU per checked-in modelDescription/<Model>.xml (the packager writes one for every
# FMU crate): adding an FMU changes no list here.
MODELS = sorted(path.stem for path in (ROOT / "modelDescription").glob("*.xml"))
INTERFACES = ["CoSimulation", "ModelExchange"]


def package_source(folder: Path) -> Path:
    """`folder` made a copy of what `pip install` of the harness reads (what the sdist
    holds: robofmu/, pyproject.toml, hatch_build.py, Cargo.toml for the version, the FMUs,
    the native kernel, the reference cases, the example scenarios), so that an install
    leaves the working tree alone."""
    ignore = shutil.ignore_patterns("__pycache__")
    for name in ("robofmu", "scenarios", "tests/references"):
        shutil.copytree(ROOT / name, folder / name, ignore=ignore)
    for name in ("pyproject.toml", "README.md", "CHANGELOG.md", "Cargo.toml", "hatch_build.py",
                 "target/release/libcosim_kernel.so"):
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / name, folder / name)
    shutil.copytree(DIST, folder / "dist", ignore=shutil.ignore_patterns("*.zip", "*.tmp"))
    return folder


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
