"""Builds examples/integrator/ into an FMI 2.0 co-simulation FMU for this machine:
``python examples/integrator/build_fmu.py OUT.fmu`` (needs a C compiler, `cc`, and FMPy,
whose FMI headers it compiles against). The FMU stands for anyone's FMU: it is not
one of robofmu's. `build` also builds examples/integrator3/, the FMI 3.0 one: an
example folder holds modelDescription.xml and one C file, compiled into the library
its CoSimulation modelIdentifier names, in the binaries folder of its FMI version."""

import platform
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path
from xml.etree import ElementTree

import fmpy

HERE = Path(__file__).resolve().parent
SUFFIX = {"Linux": ".so", "Darwin": ".dylib"}
# The binaries folder of this machine, per FMI version.
FOLDERS = {
    "2.0": {("Linux", "x86_64"): "linux64", ("Linux", "aarch64"): "linux64",
            ("Darwin", "x86_64"): "darwin64", ("Darwin", "arm64"): "darwin64"},
    "3.0": {("Linux", "x86_64"): "x86_64-linux", ("Linux", "aarch64"): "aarch64-linux",
            ("Darwin", "x86_64"): "x86_64-darwin", ("Darwin", "arm64"): "aarch64-darwin"},
}


def build(out: Path, example: Path = HERE) -> Path:
    """Compiles the C file of the folder `example` and writes the FMU `out`."""
    description = example / "modelDescription.xml"
    root = ElementTree.parse(description).getroot()
    identifier = root.find("CoSimulation").get("modelIdentifier")
    folder = FOLDERS[root.get("fmiVersion")][(platform.system(), platform.machine())]
    [source] = example.glob("*.c")
    headers = Path(fmpy.__file__).parent / "c-code"
    with tempfile.TemporaryDirectory() as work:
        library = Path(work) / f"{identifier}{SUFFIX[platform.system()]}"
        subprocess.run(["cc", "-shared", "-fPIC", "-O2", f"-I{headers}", "-o", str(library),
                        str(source)], check=True)
        out.parent.mkdir(parents=True, exist_ok=True)
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as fmu:
            fmu.write(description, "modelDescription.xml")
            fmu.write(library, f"binaries/{folder}/{library.name}")
    return out


def main(example: Path) -> None:
    """The command line of an example folder's build_fmu.py."""
    if len(sys.argv) != 2 or not sys.argv[1].endswith(".fmu"):
        sys.exit(f"usage: python examples/{example.name}/build_fmu.py OUT.fmu")
    print(build(Path(sys.argv[1]), example))


if __name__ == "__main__":
    main(HERE)
