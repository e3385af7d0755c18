"""Builds examples/integrator/ into an FMI 2.0 co-simulation FMU for this machine:
``python examples/integrator/build_fmu.py OUT.fmu`` (needs a C compiler, `cc`, and FMPy,
whose FMI 2.0 headers it compiles against). The FMU stands for anyone's FMU: it is not
one of robofmu's."""

import platform
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import fmpy

HERE = Path(__file__).resolve().parent
PLATFORMS = {("Linux", "x86_64"): ("linux64", ".so"), ("Linux", "aarch64"): ("linux64", ".so"),
             ("Darwin", "x86_64"): ("darwin64", ".dylib"),
             ("Darwin", "arm64"): ("darwin64", ".dylib")}


def build(out: Path) -> Path:
    """Compiles integrator.c and writes the FMU `out`."""
    folder, suffix = PLATFORMS[(platform.system(), platform.machine())]
    headers = Path(fmpy.__file__).parent / "c-code"
    with tempfile.TemporaryDirectory() as work:
        library = Path(work) / f"Integrator{suffix}"
        subprocess.run(["cc", "-shared", "-fPIC", "-O2", f"-I{headers}", "-o", str(library),
                        str(HERE / "integrator.c")], check=True)
        out.parent.mkdir(parents=True, exist_ok=True)
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as fmu:
            fmu.write(HERE / "modelDescription.xml", "modelDescription.xml")
            fmu.write(library, f"binaries/{folder}/{library.name}")
    return out


if __name__ == "__main__":
    if len(sys.argv) != 2 or not sys.argv[1].endswith(".fmu"):
        sys.exit("usage: python examples/integrator/build_fmu.py OUT.fmu")
    print(build(Path(sys.argv[1])))
