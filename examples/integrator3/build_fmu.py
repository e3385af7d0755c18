"""Builds examples/integrator3/ into an FMI 3.0 co-simulation FMU for this machine:
``python examples/integrator3/build_fmu.py OUT.fmu`` (needs a C compiler, `cc`, and FMPy,
whose FMI 3.0 headers it compiles against). The FMU stands for anyone's FMI 3.0 FMU: it
is not one of robofmu's."""

import platform
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import fmpy

HERE = Path(__file__).resolve().parent
PLATFORMS = {("Linux", "x86_64"): ("x86_64-linux", ".so"),
             ("Linux", "aarch64"): ("aarch64-linux", ".so"),
             ("Darwin", "x86_64"): ("x86_64-darwin", ".dylib"),
             ("Darwin", "arm64"): ("aarch64-darwin", ".dylib")}


def build(out: Path) -> Path:
    """Compiles integrator3.c and writes the FMU `out`."""
    folder, suffix = PLATFORMS[(platform.system(), platform.machine())]
    headers = Path(fmpy.__file__).parent / "c-code"
    with tempfile.TemporaryDirectory() as work:
        library = Path(work) / f"Integrator3{suffix}"
        subprocess.run(["cc", "-shared", "-fPIC", "-O2", f"-I{headers}", "-o", str(library),
                        str(HERE / "integrator3.c")], check=True)
        out.parent.mkdir(parents=True, exist_ok=True)
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as fmu:
            fmu.write(HERE / "modelDescription.xml", "modelDescription.xml")
            fmu.write(library, f"binaries/{folder}/{library.name}")
    return out


if __name__ == "__main__":
    if len(sys.argv) != 2 or not sys.argv[1].endswith(".fmu"):
        sys.exit("usage: python examples/integrator3/build_fmu.py OUT.fmu")
    print(build(Path(sys.argv[1])))
