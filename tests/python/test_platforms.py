"""The five platforms of every FMU (docs/interoperability.md, "Platforms").

scripts/build-fmus.sh cross-builds each FMU crate for x86_64-linux, aarch64-linux,
x86_64-windows, x86_64-darwin and aarch64-darwin and records in
target/toolchain/platforms.txt which ones it built; a platform it could not build is
reported here as skipped with its reason, never as passed.

- Layout: every FMU of dist/, dist/fmi3/ and dist/fmi3-scalar/ holds the binaries/
  entries of the checked-in modelDescription/binaries/<Model>.txt (the packager's drift
  check keeps that file equal to the code), and the file type of each, read by LLVM's
  llvm-readobj (rustup's llvm-tools; a universal file's slices listed by llvm-objdump),
  is the platform's; the same platform's library is the same bytes in the three FMUs
  of a model.
- Statically, every library: exported fmi2*/fmi3* functions = the functions FMPy binds
  for FMI 2.0 and FMI 3.0 (an independent list: FMPy's source); Linux: at most
  GLIBC_2.17 and only glibc's libraries; Windows: only DLLs Windows ships; macOS:
  only libSystem, the minimum macOS version, an ad-hoc code signature on arm64.
- Running: every reference case of tests/references through the FMI 2.0 host
  robofmu-platform-host (a binary of crates/test/fmi-host), cross-built for each
  platform: natively on x86_64 Linux (whose
  result must match the reference within the case's Co-Simulation tolerance: the
  host is right), under Wine (x86_64-windows) and qemu-aarch64 (aarch64-linux), whose
  results must equal x86_64 Linux's bit for bit, except the plant's on Windows (to
  1e-12; measured 1.9e-18: see NOT_BIT_IDENTICAL).
- Leaving a callback (docs/reliability.md, "Leaving a callback"): crates/test/hostile/native/
  leave.c built for aarch64 Linux (pthread_exit, pthread_cancel, longjmp under qemu) and
  with MinGW-w64's g++ for Windows (a C++ exception out of every callback the FMUs call,
  longjmp, under Wine): the documented outcome every time.
"""

import csv
import inspect
import json
import os
import re
import shutil
import sys
import struct
import subprocess
import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description

from conftest import DIST, MODELS, REFERENCES, ROOT

RECORD = ROOT / "target" / "toolchain" / "platforms.txt"
VARIANTS = {"fmi2": "", "fmi3": "fmi3", "fmi3-scalar": "fmi3-scalar"}
# tuple -> (Rust target, llvm-readobj's format and architecture of its library)
PLATFORMS = {
    "x86_64-linux": ("x86_64-unknown-linux-gnu", "elf64-x86-64 x86_64"),
    "aarch64-linux": ("aarch64-unknown-linux-gnu", "elf64-littleaarch64 aarch64"),
    "x86_64-windows": ("x86_64-pc-windows-gnu", "COFF-x86-64 x86_64"),
    "x86_64-darwin": ("x86_64-apple-darwin", "Mach-O 64-bit x86-64 x86_64"),
    "aarch64-darwin": ("aarch64-apple-darwin", "Mach-O arm64 aarch64"),
}
# The minimum macOS version of each Mach-O library: Rust's default deployment targets
# (rustc's x86_64-apple-darwin and aarch64-apple-darwin targets), stated in
# docs/interoperability.md.
MIN_MACOS = {"x86_64-darwin": (10, 12), "aarch64-darwin": (11, 0)}
# What Windows itself ships (System32): the only DLLs a Windows binary may import.
WINDOWS_DLLS = {
    "kernel32.dll", "ntdll.dll", "advapi32.dll", "bcryptprimitives.dll", "userenv.dll",
    "ws2_32.dll", "msvcrt.dll", "api-ms-win-core-synch-l1-2-0.dll", "shell32.dll",
    "ole32.dll", "user32.dll", "bcrypt.dll", "secur32.dll",
}
# libgcc_s.so.1: the unwinder of the process (every glibc system has it; glibc loads it
# for pthread_cancel), which the FMUs use instead of a copy of their own (issue 42).
GLIBC_LIBRARIES = {"libc.so.6", "libm.so.6", "libdl.so.2", "libpthread.so.0", "librt.so.1",
                   "ld-linux-x86-64.so.2", "ld-linux-aarch64.so.1", "libgcc_s.so.1"}


def status():
    """tuple -> None (built) or the reason it is missing, from build-fmus.sh's record."""
    if not RECORD.exists():
        pytest.fail(f"{RECORD} is missing: run `bash scripts/build-fmus.sh` first")
    out = {}
    for line in RECORD.read_text().splitlines():
        tuple_, state, *reason = line.split(" ", 2)
        out[tuple_] = None if state == "built" else " ".join(reason)
    return out


def require(platform):
    """Skips (with build-fmus.sh's reason) a test of a platform that was not built."""
    reason = status().get(platform, "not in target/toolchain/platforms.txt")
    if reason is not None:
        pytest.skip(f"{platform} was not built: {reason}")


def llvm(tool):
    """An LLVM tool: rustup's llvm-tools component, else Debian's `llvm` package
    (scripts/install-platform-test-tools.sh installs one of them)."""
    sysroot = subprocess.check_output(["rustc", "--print", "sysroot"], text=True).strip()
    host = re.search(r"host: (\S+)", subprocess.check_output(["rustc", "-vV"], text=True))
    path = Path(sysroot) / "lib" / "rustlib" / host.group(1) / "bin" / tool
    if path.exists():
        return str(path)
    found = shutil.which(tool)
    if not found:
        pytest.fail(f"{tool} is missing: run `bash scripts/install-platform-test-tools.sh`")
    return found


def run(*args):
    return subprocess.run(args, capture_output=True, text=True, check=True).stdout


def layout(model):
    """(fmu path relative to dist/, entry, holders) of modelDescription/binaries/<Model>.txt."""
    rows = []
    for line in (ROOT / "modelDescription" / "binaries" / f"{model}.txt").read_text().splitlines():
        if line and not line.startswith("#"):
            fmu, entry, *holders = line.split()
            rows.append((fmu, entry, holders))
    return rows


def library(model, platform):
    """The bytes of `model`'s library for `platform`, from its FMI 3.0 FMU."""
    description = ET_identifier(model)
    entry = f"binaries/{platform}/{description}{'.dll' if 'windows' in platform else '.dylib' if 'darwin' in platform else '.so'}"
    with zipfile.ZipFile(DIST / "fmi3" / f"{model}.fmu") as z:
        return z.read(entry)


def ET_identifier(model):
    return read_model_description(str(DIST / f"{model}.fmu")).coSimulation.modelIdentifier


def extract(tmp_path, model, platform):
    data = library(model, platform)
    path = tmp_path / f"{model}-{platform}.bin"
    path.write_bytes(data)
    return path


# ---------------------------------------------------------------- layout and file types

@pytest.mark.parametrize("platform", PLATFORMS)
@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("model", MODELS)
def test_each_fmu_holds_the_platform_binary_of_its_layout(model, variant, platform, tmp_path):
    require(platform)
    fmu_name = str(Path(VARIANTS[variant]) / f"{model}.fmu")
    rows = [(entry, holders) for fmu, entry, holders in layout(model)
            if fmu == fmu_name and platform in holders]
    assert len(rows) == 1, f"{fmu_name}: layout has {rows} for {platform}"
    entry, holders = rows[0]
    with zipfile.ZipFile(DIST / fmu_name) as z:
        names = [n for n in z.namelist() if n.startswith("binaries/")]
        assert entry in names, f"{fmu_name}: no {entry} ({names})"
        data = z.read(entry)
    path = tmp_path / Path(entry).name
    path.write_bytes(data)
    objdump = llvm("llvm-objdump")
    if len(holders) == 1:
        files = {platform: path}
    else:
        # A universal Mach-O file (FMI 2.0's darwin64): llvm-objdump lists its slices;
        # each must be the platform's library of the FMI 3.0 FMU, byte for byte.
        headers = run(objdump, "--macho", "--universal-headers", str(path))
        arch_of = {"CPU_TYPE_X86_64": "x86_64-darwin", "CPU_TYPE_ARM64": "aarch64-darwin"}
        files = {}
        for block in headers.split("architecture ")[1:]:
            holder = arch_of[re.search(r"cputype (\S+)", block).group(1)]
            offset = int(re.search(r"offset (\d+)", block).group(1))
            size = int(re.search(r"size (\d+)", block).group(1))
            files[holder] = tmp_path / holder
            files[holder].write_bytes(data[offset:offset + size])
        built = sorted(h for h in holders if status().get(h) is None)
        assert sorted(files) == built, (entry, headers)
    # Expected: llvm-readobj's format and architecture of the platform.
    for holder, file in files.items():
        headers = run(llvm("llvm-readobj"), "--file-headers", str(file))
        kind = " ".join(re.search(rf"^{k}: (.+)$", headers, re.M).group(1) for k in ("Format", "Arch"))
        assert kind == PLATFORMS[holder][1], (entry, holder, kind)
        # The same library in the FMI 2.0, FMI 3.0 and scalar FMUs.
        assert file.read_bytes() == library(model, holder)


@pytest.mark.parametrize("platform", PLATFORMS)
def test_the_stepping_kernel_is_built_for_the_platform_and_goes_into_the_wheel(platform):
    # hatch_build.py bundles, per platform, the kernel build-fmus.sh cross-built beside
    # the FMUs; robofmu.loop loads it from robofmu/_native/<that platform's PLATFORM>/.
    require(platform)
    sys.path.insert(0, str(ROOT))
    try:
        from hatch_build import CROSS_KERNELS, kernels
    finally:
        sys.path.remove(str(ROOT))
    target = PLATFORMS[platform][0]
    folder = next(f for t, f, _ in CROSS_KERNELS if t == target)
    path = kernels(ROOT)[folder]
    assert path.parent == ROOT / "target" / target / "fmu", path
    headers = run(llvm("llvm-readobj"), "--file-headers", str(path))
    kind = " ".join(re.search(rf"^{k}: (.+)$", headers, re.M).group(1) for k in ("Format", "Arch"))
    assert kind == PLATFORMS[platform][1], kind
    # Expected: the two entry points robofmu/loop.py declares (argtypes) and calls.
    assert {"cosim_kernel_run", "cosim_kernel_propagate"} <= exported(path, platform)
    if platform.endswith("linux"):
        symbols = run(llvm("llvm-objdump"), "-T", str(path))
        versions = {tuple(int(x) for x in v.split(".")) for v in re.findall(r"GLIBC_([0-9.]+)", symbols)}
        assert max(versions, default=(0,)) <= (2, 17), sorted(versions)
    if platform.endswith("windows"):
        dlls = {d.lower() for d in re.findall(r"DLL Name: (\S+)", run(llvm("llvm-objdump"), "-p", str(path)))}
        assert dlls and dlls <= WINDOWS_DLLS, dlls - WINDOWS_DLLS


# ---------------------------------------------------------------- static checks

def fmpy_functions(prefix):
    """Every fmi2*/fmi3* function FMPy's classes bind (their source): an importer's list."""
    import fmpy.fmi2
    import fmpy.fmi3
    classes = {
        "fmi2": [fmpy.fmi2._FMU2, fmpy.fmi2.FMU2Model, fmpy.fmi2.FMU2Slave],
        "fmi3": [fmpy.fmi3._FMU3, fmpy.fmi3.FMU3Model, fmpy.fmi3.FMU3Slave,
                 fmpy.fmi3.FMU3ScheduledExecution],
    }[prefix]
    names = set()
    for cls in classes:
        names |= set(re.findall(rf"[\"']({prefix}[A-Z]\w+)[\"']", inspect.getsource(cls)))
        names |= {n for n in vars(cls) if n.startswith(prefix)}
    return names


def exported(path, platform):
    """The names a library exports, read by llvm-nm (Mach-O: the leading _ dropped)."""
    if platform.endswith("windows"):
        text = run(llvm("llvm-objdump"), "-p", str(path))
        table = text.split("Export Table:", 1)[1]
        return set(re.findall(r"^\s+\d+\s+0x[0-9a-f]+\s+(\S+)$", table, re.M))
    args = ["--defined-only", "--extern-only", "--format=just-symbols"]
    if platform.endswith("linux"):
        args.append("-D")
    names = run(llvm("llvm-nm"), *args, str(path)).split()
    return {n[1:] if platform.endswith("darwin") else n for n in names}


@pytest.mark.parametrize("platform", PLATFORMS)
@pytest.mark.parametrize("model", MODELS)
def test_the_library_exports_the_fmi_functions_and_no_other(model, platform, tmp_path):
    require(platform)
    path = extract(tmp_path, model, platform)
    names = exported(path, platform)
    fmi = {n for n in names if n.startswith(("fmi2", "fmi3"))}
    # Expected: FMPy's FMI 2.0 and 3.0 function lists, plus the packager's symbol.
    assert fmi == fmpy_functions("fmi2") | fmpy_functions("fmi3")
    assert "robofmu_fmu_description" in names
    if not platform.endswith("darwin"):
        assert names - fmi == {"robofmu_fmu_description"}
        return
    # macOS: zig's Mach-O linker ignores rustc's exported-symbols list; link-time
    # optimisation makes every Rust symbol but the exported ones internal, and what
    # stays global besides is the Rust runtime's personality routine, the
    # standard library's empty panic payload and the two symbols the linker defines
    # (docs/interoperability.md).
    rest = {n for n in names - fmi if not n.endswith("EMPTY_PANIC")}
    assert rest == {"robofmu_fmu_description", "rust_eh_personality", "__dso_handle",
                    "_mh_dylib_header"}


@pytest.mark.parametrize("platform", ["x86_64-darwin", "aarch64-darwin"])
@pytest.mark.parametrize("model", MODELS)
def test_the_macos_library_keeps_no_local_symbol(model, platform, tmp_path):
    """Stripped without a post-link strip (which would void the arm64 signature): the
    symbol table holds the exported symbols and the imported ones, nothing else."""
    require(platform)
    path = extract(tmp_path, model, platform)
    nm = llvm("llvm-nm")
    defined = run(nm, "--defined-only", "--format=just-symbols", str(path)).split()
    extern = run(nm, "--defined-only", "--extern-only", "--format=just-symbols", str(path)).split()
    assert sorted(defined) == sorted(extern)


@pytest.mark.parametrize("platform", ["x86_64-linux", "aarch64-linux"])
@pytest.mark.parametrize("model", MODELS)
def test_the_linux_library_loads_on_glibc_2_17(model, platform, tmp_path):
    require(platform)
    path = extract(tmp_path, model, platform)
    symbols = run(llvm("llvm-objdump"), "-T", str(path))
    versions = {tuple(int(x) for x in v.split(".")) for v in re.findall(r"GLIBC_([0-9.]+)", symbols)}
    assert versions and max(versions) <= (2, 17), sorted(versions)
    needed = set(re.findall(r"NEEDED\s+(\S+)", run(llvm("llvm-objdump"), "-p", str(path))))
    assert needed <= GLIBC_LIBRARIES, needed


@pytest.mark.parametrize("model", MODELS)
def test_the_windows_library_needs_only_what_windows_ships(model, tmp_path):
    require("x86_64-windows")
    path = extract(tmp_path, model, "x86_64-windows")
    dlls = {d.lower() for d in re.findall(r"DLL Name: (\S+)", run(llvm("llvm-objdump"), "-p", str(path)))}
    # Expected: no libgcc_s_seh-1.dll, libwinpthread-1.dll or other MinGW runtime DLL.
    assert dlls and dlls <= WINDOWS_DLLS, dlls - WINDOWS_DLLS


def load_commands(data):
    """(cmd, bytes of the command) of a thin 64-bit little-endian Mach-O file, read with
    the layout of <mach-o/loader.h> (mach_header_64, then ncmds load commands)."""
    magic, _, _, _, ncmds, _, _, _ = struct.unpack_from("<IiiIIIII", data, 0)
    assert magic == 0xFEEDFACF
    at, out = 32, []
    for _ in range(ncmds):
        cmd, size = struct.unpack_from("<II", data, at)
        out.append((cmd, data[at:at + size]))
        at += size
    return out


@pytest.mark.parametrize("platform", ["x86_64-darwin", "aarch64-darwin"])
@pytest.mark.parametrize("model", MODELS)
def test_the_macos_library_links_libsystem_and_states_its_macos(model, platform, tmp_path):
    require(platform)
    path = extract(tmp_path, model, platform)
    headers = run(llvm("llvm-objdump"), "--macho", "--dylibs-used", str(path))
    dylibs = {line.split(" (")[0].strip() for line in headers.splitlines()[1:] if line.strip()}
    # The list starts with the library's own install name (LC_ID_DYLIB): @rpath/<file>,
    # not the build folder's path.
    identity = run(llvm("llvm-objdump"), "--macho", "--dylib-id", str(path)).split()[-1]
    assert re.fullmatch(r"@rpath/librobofmu_\w+_fmu\.dylib", identity), identity
    assert dylibs - {identity} == {"/usr/lib/libSystem.B.dylib"}, dylibs
    commands = dict(load_commands(path.read_bytes()))
    LC_BUILD_VERSION, LC_VERSION_MIN_MACOSX = 0x32, 0x24
    if LC_BUILD_VERSION in commands:
        minos = struct.unpack_from("<I", commands[LC_BUILD_VERSION], 12)[0]
    else:
        minos = struct.unpack_from("<I", commands[LC_VERSION_MIN_MACOSX], 8)[0]
    assert (minos >> 16, (minos >> 8) & 0xFF) == MIN_MACOS[platform]


@pytest.mark.parametrize("model", MODELS)
def test_the_arm64_macos_library_has_an_ad_hoc_signature(model, tmp_path):
    require("aarch64-darwin")
    data = extract(tmp_path, model, "aarch64-darwin").read_bytes()
    LC_CODE_SIGNATURE = 0x1D
    commands = dict(load_commands(data))
    assert LC_CODE_SIGNATURE in commands, "no code signature: macOS on arm64 refuses to load it"
    offset, size = struct.unpack_from("<II", commands[LC_CODE_SIGNATURE], 8)
    blob = data[offset:offset + size]
    # The embedded signature super blob (big-endian): magic 0xfade0cc0, its blobs'
    # (type, offset); the code directory (magic 0xfade0c02) holds the flags, where
    # CS_ADHOC = 0x2 (<kern/cs_blobs.h>).
    magic, _, count = struct.unpack_from(">III", blob, 0)
    assert magic == 0xFADE0CC0
    flags = None
    for i in range(count):
        _, at = struct.unpack_from(">II", blob, 12 + 8 * i)
        if struct.unpack_from(">I", blob, at)[0] == 0xFADE0C02:
            flags = struct.unpack_from(">I", blob, at + 12)[0]
    assert flags is not None and flags & 0x2, f"code directory flags {flags}"


# ---------------------------------------------------------------- the reference cases, run

def cases():
    return sorted((d.parent.name, d.name) for d in REFERENCES.glob("*/*") if (d / "case.json").exists())


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(v) for v in row] for row in rows[1:]])


def plan(model, case, library_path):
    """The host's plan of a reference case (crates/test/fmi-host/src/bin/robofmu-platform-host.rs)."""
    folder = REFERENCES / model / case
    md = read_model_description(str(DIST / f"{model}.fmu"))
    variables = {v.name: v for v in md.modelVariables}
    options = dict(line.split(", ") for line in (folder / f"{model}_ref.opt").read_text().splitlines())
    start, stop, step = (float(options[k]) for k in ("StartTime", "StopTime", "StepSize"))
    lines = [f"library {library_path}", f"guid {md.guid}", f"start {start!r}", f"stop {stop!r}",
             f"step {step!r}"]
    for name, value in json.loads((folder / "case.json").read_text())["start_values"].items():
        v = variables[name]
        kind = {"Real": "real", "Integer": "integer", "Boolean": "boolean"}[v.type]
        shown = int(value) if kind == "boolean" else int(value) if kind == "integer" else repr(float(value))
        lines.append(f"{kind} {v.valueReference} {shown}")
    names, _ = read_csv(folder / f"{model}_ref.csv")
    outputs = names[1:]
    inputs = folder / f"{model}_input.csv"
    if inputs.exists():
        in_names, table = read_csv(inputs)
        lines.append("inputs " + " ".join(str(variables[n].valueReference) for n in in_names[1:]))
        steps = round((stop - start) / step)
        for k in range(steps + 1):
            t = start + k * step
            # Linear interpolation in time, as FMPy's Input applies a continuous input.
            values = [np.interp(t, table[:, 0], table[:, j]) for j in range(1, len(in_names))]
            lines.append("at " + " ".join(repr(float(x)) for x in values))
    lines.append("outputs " + " ".join(str(variables[n].valueReference) for n in outputs))
    return "\n".join(lines) + "\n", outputs


def host(platform):
    target = PLATFORMS[platform][0]
    exe = ROOT / "target" / target / "fmu" / ("robofmu-platform-host" + (".exe" if "windows" in platform else ""))
    if not exe.exists():
        pytest.fail(f"{exe} is missing: run `bash scripts/build-fmus.sh`")
    return exe


def wine():
    for candidate in ("wine64", "/usr/lib/wine/wine64", "wine"):
        found = shutil.which(candidate)
        if found:
            return found
    pytest.fail("Wine is missing: run `bash scripts/install-platform-test-tools.sh`")


def qemu():
    found = shutil.which("qemu-aarch64")
    if not found or not Path("/usr/aarch64-linux-gnu/lib").exists():
        pytest.fail("qemu-aarch64 or the aarch64 glibc is missing: run "
                    "`bash scripts/install-platform-test-tools.sh`")
    return found


@pytest.fixture(scope="module")
def windows_folder(tmp_path_factory):
    """The Windows host with the test-only bcryptprimitives.dll beside it (Wine 8 lacks
    that DLL; see tests/platforms/bcryptprimitives.c), and a Wine prefix of its own whose
    wineserver and services stay up until the module's tests end (a Wine process then
    starts in about 0.1 s instead of 2.5 to 4 s)."""
    require("x86_64-windows")
    folder = tmp_path_factory.mktemp("windows")
    shutil.copy(host("x86_64-windows"), folder / "host.exe")
    # MinGW-w64's gcc: scripts/build-fmus.sh links the Windows binaries with it.
    subprocess.run(["x86_64-w64-mingw32-gcc", "-shared", "-O2", "-o",
                    str(folder / "bcryptprimitives.dll"),
                    str(ROOT / "tests" / "platforms" / "bcryptprimitives.c"), "-ladvapi32"],
                   check=True, capture_output=True, cwd=folder)
    beside = Path(wine()).resolve().with_name("wineserver")
    server = str(beside) if beside.exists() else shutil.which("wineserver") or "wineserver"
    (folder / "prefix").mkdir()
    env = dict(os.environ, WINEPREFIX=str(folder / "prefix"))
    subprocess.run([server, "-p"], check=True, env=env)
    # The prefix's services outlive the process that starts them: started here, they do
    # not hold a test's output pipes open.
    subprocess.run([wine(), "wineboot", "--init"], check=True, env=dict(env, WINEDEBUG="-all"),
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=300)
    yield folder
    subprocess.run([server, "-k"], env=env)


def simulate(platform, model, case, tmp_path, windows_folder=None):
    """The host's output lines on `platform` as an array (time first)."""
    folder = tmp_path / platform
    folder.mkdir()
    lib = extract(folder, model, platform)
    if platform == "x86_64-windows":
        lib = lib.rename(folder / f"{model}.dll")
    env = dict(os.environ)
    if platform == "x86_64-windows":
        env.update(WINEDEBUG="-all", WINEPREFIX=str(windows_folder / "prefix"),
                   WINEDLLOVERRIDES="mscoree,mshtml=")
        text, outputs = plan(model, case, "Z:" + str(lib).replace("/", "\\"))
        command = [wine(), str(windows_folder / "host.exe")]
    elif platform == "aarch64-linux":
        text, outputs = plan(model, case, lib)
        command = [qemu(), "-L", "/usr/aarch64-linux-gnu", str(host(platform))]
    else:
        text, outputs = plan(model, case, lib)
        command = [str(host(platform))]
    plan_path = folder / "plan.txt"
    plan_path.write_text(text)
    if platform == "x86_64-windows":
        plan_path = "Z:" + str(plan_path).replace("/", "\\")
    done = subprocess.run(command + [str(plan_path)], capture_output=True, text=True, env=env,
                          timeout=600)
    assert done.returncode == 0, f"{platform}: {done.stderr[-2000:]}"
    rows = [[float(v) for v in line.split()] for line in done.stdout.splitlines() if line.strip()]
    return outputs, np.array(rows)


def tolerances(model, case, outputs):
    info = json.loads((REFERENCES / model / case / "case.json").read_text())
    return np.array([info["tolerances"]["CoSimulation"][n] for n in outputs])


@pytest.mark.parametrize("model,case", cases())
def test_the_x86_64_linux_host_reproduces_the_reference(model, case, tmp_path):
    require("x86_64-linux")
    outputs, result = simulate("x86_64-linux", model, case, tmp_path)
    names, reference = read_csv(REFERENCES / model / case / f"{model}_ref.csv")
    # Expected: the reference (closed forms, scripts/make_references.py) on its time grid,
    # within the case's Co-Simulation tolerance.
    assert result.shape == reference.shape
    np.testing.assert_allclose(result[:, 0], reference[:, 0], rtol=0, atol=1e-12)
    error = np.abs(result[:, 1:] - reference[:, 1:]).max(axis=0)
    assert np.all(error <= tolerances(model, case, outputs)), dict(zip(outputs, error))


# The (model, platform) pairs whose results are not bit-identical to x86_64 Linux, and
# why: the plant integrates trigonometric functions, which Rust takes from the C
# runtime (glibc on Linux, msvcrt on Windows), and msvcrt rounds some sin/cos results
# differently in the last bit. Measured: at most 1.9e-18 (angles and rates of order 1,
# both plant cases, 2001 points); the bound is 1e-12, eight orders tighter than the
# cases' tolerances (1e-4, 2e-4). Every other pair is asserted bit for bit.
NOT_BIT_IDENTICAL = {("Pss3Plant", "x86_64-windows")}
PLATFORM_TOLERANCE = 1e-12


@pytest.mark.parametrize("platform", ["x86_64-windows", "aarch64-linux"])
@pytest.mark.parametrize("model,case", cases())
def test_the_platform_gives_the_x86_64_linux_result(model, case, platform, tmp_path, request):
    require("x86_64-linux")
    require(platform)
    folder = request.getfixturevalue("windows_folder") if platform == "x86_64-windows" else None
    outputs, native = simulate("x86_64-linux", model, case, tmp_path)
    _, other = simulate(platform, model, case, tmp_path, folder)
    assert other.shape == native.shape
    difference = np.abs(other - native).max(axis=0)
    message = (f"{platform} differs from x86_64-linux: max |diff| per column {difference} "
               f"(case tolerance {tolerances(model, case, outputs)})")
    if (model, platform) in NOT_BIT_IDENTICAL:
        # Expected: x86_64 Linux's result to 1e-12 (see NOT_BIT_IDENTICAL).
        assert np.all(difference <= PLATFORM_TOLERANCE), message
    else:
        # Expected: x86_64 Linux's result bit for bit (the same Rust code, IEEE
        # arithmetic, the same results of the C runtime's functions).
        assert np.array_equal(other, native), message


# ---------------------------------------------------------------- leaving a callback on aarch64

ZIG = ROOT / "target" / "toolchain" / "venv" / "bin" / "python"
ABORTED = "robofmu FMU: fatal: the host's {} callback did not return"


@pytest.fixture(scope="module")
def leave_host_aarch64(tmp_path_factory):
    """crates/test/hostile/native/leave.c built as a C host for aarch64 Linux by zig (the
    toolchain of scripts/build-fmus.sh): glibc's pthread_exit and pthread_cancel unwind
    with libgcc_s, as a gcc-built host does."""
    require("aarch64-linux")
    if not ZIG.exists():
        pytest.fail(f"{ZIG} is missing: run `bash scripts/build-fmus.sh`")
    out = tmp_path_factory.mktemp("leave") / "leave-c"
    subprocess.run([str(ZIG), "-m", "ziglang", "cc", "-target", "aarch64-linux-gnu.2.17", "-O1",
                    "-x", "c", str(ROOT / "crates" / "test" / "hostile" / "native" / "leave.c"),
                    "-o", str(out), "-lpthread", "-ldl"], check=True, capture_output=True)
    return out


# (standard, way, callback): every way out of the logger, and the unwinding ways out of
# intermediateUpdate (FMI 3.0; the models without intermediate points never call it).
AARCH64_LEAVES = [(standard, way, "logger") for standard in ("2", "3")
                  for way in ("exit", "cancel", "longjmp")] + [
                  ("3", "exit", "update"), ("3", "cancel", "update")]


@pytest.mark.parametrize("standard,way,callback", AARCH64_LEAVES)
@pytest.mark.parametrize("model", MODELS)
def test_leaving_a_callback_on_aarch64_is_an_abort_or_the_error_state(
        model, standard, way, callback, leave_host_aarch64, tmp_path):
    # Expected (docs/reliability.md, "Leaving a callback"), as crates/test/hostile/tests/leave.rs
    # checks on x86_64: pthread_exit or pthread_cancel in the callback ends the process
    # with SIGABRT and the FMU's message naming the callback; after a longjmp the next
    # call finds the Error state (3), Reset (0) makes the instance usable and
    # FreeInstance frees it. A model without intermediate points: the step returns.
    path = extract(tmp_path, model, "aarch64-linux")
    token = read_model_description(str(DIST / f"{model}.fmu")).guid
    result = subprocess.run([qemu(), "-L", "/usr/aarch64-linux-gnu", str(leave_host_aarch64),
                             str(path), standard, token, way, callback],
                            capture_output=True, text=True, timeout=120)
    # qemu-user reports the guest's SIGABRT as its own (-6, or 128 + 6 from a shell).
    judge_leave(result, model, standard, way, callback, aborted=(-6, 134))


def judge_leave(result, model, standard, way, callback, aborted):
    """Asserts the documented outcome of a leave.c run (docs/reliability.md, "Leaving a
    callback"); `aborted`: the exit statuses of an aborted process on the platform."""
    if way == "longjmp":
        enter = "enter 0\n" if standard == "2" else ""
        assert (result.returncode, result.stdout) == (
            0, f"left\nagain 3\nreset 0\nstart 0\n{enter}exit 0\nstep 0\nfreed\njoined\n"), result
    elif callback == "update" and not has_intermediate_points(model):
        assert (result.returncode, result.stdout) == (0, "returned\njoined\n"), result
    else:
        assert result.stdout == "left\n", result
        assert ABORTED.format(callback_name(standard, callback)) in result.stderr, result
        assert result.returncode in aborted, result


def has_intermediate_points(model):
    """Whether the FMI 3.0 `model` declares intermediateUpdate variables: the models whose
    fmi3DoStep calls the intermediateUpdate callback (docs/fmi-layer.md)."""
    with zipfile.ZipFile(DIST / "fmi3" / f"{model}.fmu") as z:
        return 'intermediateUpdate="true"' in z.read("modelDescription.xml").decode()


def callback_name(standard, callback):
    """The callback's name in the FMU's abort message (leave.c's `logger` or `update`)."""
    if callback == "update":
        return "intermediateUpdate"
    return "logger" if standard == "2" else "logMessage"


# ---------------------------------------------------------------- leaving a callback on Windows

@pytest.fixture(scope="module")
def leave_host_windows(windows_folder):
    """crates/test/hostile/native/leave.c built as a C++ host for Windows by MinGW-w64's g++
    (SEH exceptions, as a MinGW C++ importer throws them), statically linked, beside the
    platform host in the Wine folder."""
    compiler = shutil.which("x86_64-w64-mingw32-g++-posix")
    if not compiler:
        pytest.fail("MinGW-w64's g++ is missing: run `bash scripts/install-platform-test-tools.sh`")
    out = windows_folder / "leave.exe"
    subprocess.run([compiler, "-O1", "-Wall", "-Werror", "-static",
                    "-x", "c++", str(ROOT / "crates" / "test" / "hostile" / "native" / "leave.c"),
                    "-o", str(out)], check=True, capture_output=True)
    return out


# (way, callback): a C++ exception out of every callback the FMUs call (FMI 2.0 logger,
# FMI 3.0 logMessage and intermediateUpdate), and a longjmp out of the logger.
WINDOWS_LEAVES = [("2", "throw", "logger"), ("2", "longjmp", "logger"),
                  ("3", "throw", "logger"), ("3", "throw", "update"), ("3", "longjmp", "logger")]


@pytest.mark.parametrize("standard,way,callback", WINDOWS_LEAVES)
@pytest.mark.parametrize("model", MODELS)
def test_leaving_a_callback_on_windows_is_an_abort_or_the_error_state(
        model, standard, way, callback, leave_host_windows, tmp_path):
    # Expected (docs/reliability.md, "Leaving a callback"), as on Linux: a C++ exception
    # thrown out of the callback ends the process through abort() (msvcrt: exit status
    # 3) with the FMU's message naming the callback; the host's catch is never reached.
    # After a longjmp the next call finds the Error state (3), Reset (0) makes the
    # instance usable and FreeInstance frees it. A model without intermediate points
    # never calls intermediateUpdate: the step returns.
    path = extract(tmp_path, model, "x86_64-windows").rename(tmp_path / f"{model}.dll")
    token = read_model_description(str(DIST / f"{model}.fmu")).guid
    env = dict(os.environ, WINEDEBUG="-all", WINEPREFIX=str(leave_host_windows.parent / "prefix"),
               WINEDLLOVERRIDES="mscoree,mshtml=")
    result = subprocess.run([wine(), str(leave_host_windows), "Z:" + str(path).replace("/", "\\"),
                             standard, token, way, callback],
                            capture_output=True, text=True, timeout=300, env=env)
    # msvcrt's abort() exits with status 3.
    judge_leave(result, model, standard, way, callback, aborted=(3,))
