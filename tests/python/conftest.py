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


def fmu3(path, directory, model_exchange=False, guid=None, lines=None, **instantiate):
    """FMPy's FMU3Slave (FMU3Model with `model_exchange`) of the FMI 3.0 FMU at `path`,
    extracted into `directory` and instantiated with FMPy's `instantiate` arguments
    (`guid`: another instantiation token). Added to the FMPy object: `description`, `vr`
    (value reference by name) and `lines`, what the FMU logged as (status, category,
    message), `lines` when given (it outlives a refused instantiation). A call whose
    status matters goes through FMPy's ctypes function, `fmu.dll.fmi3...`: FMPy's
    methods raise FMICallException from fmi3Error on."""
    from fmpy import extract, read_model_description
    from fmpy.fmi3 import FMU3Model, FMU3Slave

    root = extract(path, unzipdir=str(directory))
    description = read_model_description(root)
    cls = FMU3Model if model_exchange else FMU3Slave
    fmu = cls(guid=guid or description.guid, unzipDirectory=root,
              modelIdentifier=description.coSimulation.modelIdentifier)
    fmu.description = description
    fmu.vr = {v.name: v.valueReference for v in description.modelVariables}
    fmu.lines = [] if lines is None else lines

    def log(_env, status, category, message):
        fmu.lines.append((status, category.decode(), message.decode()))

    fmu.instantiate(logMessage=log, **instantiate)
    return fmu


def refused(call, *args):
    """The status with which the FMPy call `call(*args)` failed (FMICallException)."""
    from fmpy.fmi1 import FMICallException

    with pytest.raises(FMICallException) as failure:
        call(*args)
    return failure.value.status
