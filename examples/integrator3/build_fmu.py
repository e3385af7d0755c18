"""Builds examples/integrator3/ into an FMI 3.0 co-simulation FMU for this machine:
``python examples/integrator3/build_fmu.py OUT.fmu`` (needs a C compiler, `cc`, and FMPy,
whose FMI 3.0 headers it compiles against), with the builder of examples/integrator/.
The FMU stands for anyone's FMI 3.0 FMU: it is not one of robofmu's."""

import runpy
from pathlib import Path

HERE = Path(__file__).resolve().parent
_BUILDER = runpy.run_path(str(HERE.parent / "integrator" / "build_fmu.py"))


def build(out: Path) -> Path:
    """Compiles integrator3.c and writes the FMU `out`."""
    return _BUILDER["build"](out, HERE)


if __name__ == "__main__":
    _BUILDER["main"](HERE)
