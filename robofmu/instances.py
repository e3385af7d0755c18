"""One FMI 2.0 co-simulation instance per FMU file, shared in this process by the checks
of a scenario (its parameters, the workspace, the input-derivative probes) and by its
runs: each borrows the idle instance of its file (fmi2Reset and the experiment set up
again) or instantiates one when none is idle, and gives it back when done. An instance
whose use failed is closed, never given back, and a failed run closes every idle one.
So a scenario's FMUs are instantiated once each before the first step, and a second run
of a loaded scenario instantiates nothing (tests/python/test_instantiations.py). The
idle instances are closed at exit (close_all), and by the command line after each
command."""

from __future__ import annotations

import atexit
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from .errors import CosimError, ScenarioError
from .fmi2 import FmuInstance
from .fmu_check import describe

_idle: dict[tuple[str, int], FmuInstance] = {}


def _key(path: Path) -> tuple[str, int]:
    resolved = Path(path).resolve()
    return str(resolved), resolved.stat().st_mtime_ns


def open_instance(alias: str, path: Path, start_time: float, stop_time: float) -> FmuInstance:
    """An instance of the FMU at `path`, named `alias` in messages, ready for its start
    values (the state after fmi2SetupExperiment)."""
    try:
        key = _key(path)
    except OSError:
        return new_instance(alias, path, start_time, stop_time)  # its own message
    fmu = _idle.pop(key, None)
    if fmu is not None:
        fmu.alias = alias
        try:
            fmu.reset(start_time, stop_time)
            fmu.pool_key = key
            return fmu
        except CosimError:
            fmu.close()
    fmu = new_instance(alias, path, start_time, stop_time)
    fmu.pool_key = key
    return fmu


def new_instance(alias: str, path: Path, start_time: float, stop_time: float) -> FmuInstance:
    """A new instance of the FMU at `path`: FMI 2.0 (robofmu.fmi2), or an FMI 3.0 FMU of
    anyone's (robofmu.fmi3, addressed by the scalar names of robofmu.fmu_check's view;
    its inputs held over each step: no input derivatives)."""
    try:
        version = describe(Path(path), "fmus").fmiVersion
    except ScenarioError:
        version = "2.0"  # FmuInstance says what is wrong with the file
    if version == "3.0":
        from .fmi3 import Fmu3Instance  # lazily: FMPy's FMI 3.0 layer
        return Fmu3Instance(alias, Path(path), start_time, stop_time)  # type: ignore[return-value]
    return FmuInstance(alias, Path(path), start_time, stop_time)


def give_back(fmu: FmuInstance) -> None:
    """`fmu` made idle for the next user of its file (one kept per file), else closed."""
    key = getattr(fmu, "pool_key", None)
    if key is None or getattr(fmu, "_fmu", None) is None or key in _idle:
        fmu.close()
        return
    _idle[key] = fmu


@contextmanager
def borrowed(alias: str, path: Path, start_time: float = 0.0,
             stop_time: float = 1.0) -> Iterator[FmuInstance]:
    """open_instance for the block; given back after it, closed when it raised."""
    fmu = open_instance(alias, path, start_time, stop_time)
    try:
        yield fmu
    except BaseException:
        fmu.close()
        raise
    give_back(fmu)


def close_all() -> None:
    """Closes every idle instance (their extracted folders removed)."""
    while _idle:
        _idle.popitem()[1].close()


atexit.register(close_all)
