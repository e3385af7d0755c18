"""Writes the compatibility information the FMI tools list asks each exporting tool for
(modelica/fmi-standard.org, CONTRIBUTING.md, "Compatibility information"): per FMU of
dist/ (FMI 2.0, 3.0 and 3.0 scalar-only) a folder with the files the guide names,

    <Model>.fmu, <Model>_ref.csv (at most 10 variables, at most 1 MB), <Model>_in.csv
    (models with inputs), <Model>_ref.opt, Readme.txt (what the FMU represents, what is
    tested, the importers that ran it with their versions and verdicts),

laid out as the FMI cross-check did (a layout the guide allows: "The folder structure
can be chosen by the vendor"): OUT/fmus/<FMI version>/<cs|me>/<platform>/<tool>/<version>/
<Model>/, the scalar-only FMI 3.0 FMUs under the tool name robofmu-scalar. The reference
of each FMU is its model's case at the FMU's defaults (tests/references/<Model>/, the
folder holding cross-check.txt), the smoke test the FMU carries itself (FMI-LS-REF).

Every FMU is first checked with FMPy's validate_fmu (the guide asks for a checker), then
imported by running it, not by hand: `cosim verify OUT/fmus --html` (FMPy, Co-Simulation
and Model Exchange) writes OUT/results/ (the cross-check's results layout) and
OUT/junit.xml; each Co-Simulation case is also run, in a child process each (a crash of a
library costs that case only), by
- our master (robofmu.master.Master, the native stepping loop of `cosim run`), the FMU
  with its inputs from a CSV source, held over each step;
- the container runtime of fmu-manipulation-toolbox: the FMU alone in a container FMU
  (FMI 2 or 3 like the FMU), run by `cosim verify` against the same case;
- libcosim (libcosimpy), which refuses FMI 3.0 FMUs (its refusal is recorded);
- ecos (ecospy), the FMI 2.0 and scalar-only FMI 3.0 ones;
the master, libcosim and ecos judged by cosim verify's rule (the FMI cross-check band,
robofmu.verify) from the first step on. Each Readme.txt and OUT/README.md then list the
importers with their versions, verdicts and limits, and the results page OUT/index.html
(robofmu.verify.page, as `cosim verify TREE --html` writes it) shows the matrix FMU x
importer x platform of those same verdicts, cosim's with its numbers and plots.

Usage: python scripts/compatibility.py OUT   (from the repository root; needs dist/ and
the venv). Exit status 1 when an FMU fails its verdict.
"""

from __future__ import annotations

import argparse
import importlib.metadata
import os
import re
import shutil
import subprocess
import sys
import tomllib
import xml.etree.ElementTree as ET
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import fmpy
import numpy as np
from fmpy.validation import validate_fmu

ROOT = Path(__file__).resolve().parents[1]
MAX_VARIABLES = 10
MAX_CSV_BYTES = 1_000_000
VARIANTS = [("", "2.0", "linux64", "robofmu"), ("fmi3", "3.0", "x86_64-linux", "robofmu"),
            ("fmi3-scalar", "3.0", "x86_64-linux", "robofmu-scalar")]


def version() -> str:
    """The workspace's version (Cargo.toml [workspace.package]), every FMU's."""
    with (ROOT / "Cargo.toml").open("rb") as f:
        return str(tomllib.load(f)["workspace"]["package"]["version"])


def defaults_case(model: str) -> Path:
    (marker,) = (ROOT / "tests" / "references" / model).glob("*/cross-check.txt")
    return marker.parent


def check_csv(path: Path) -> None:
    """The guide's limits: a CSV at most 1 MB, a reference of at most 10 variables (the
    inputs are every input of the FMU)."""
    header = path.read_text().splitlines()[0].split(",")
    many = path.name.endswith("_ref.csv") and len(header) - 1 > MAX_VARIABLES
    if many or path.stat().st_size > MAX_CSV_BYTES:
        sys.exit(f"compatibility: {path}: {len(header) - 1} variables, {path.stat().st_size} "
                 f"bytes; the FMI tools list allows {MAX_VARIABLES} and {MAX_CSV_BYTES}")


def write_arrays(source: Path, target: Path) -> None:
    """`source` (a case's CSV, one column per scalar, FMI 2.0's names) written at
    `target` as the guide's CSV rules ask for the FMI 3.0 build, whose arrays are
    variables: "All variable names are exactly the same as defined in the
    modelDescription.xml"; "Arrays are serialized as for start values in the
    modelDescription.xml with space (` `) as separator". The elements x[1], x[2], ...
    become one column x; the numbers are kept as written."""
    rows = [line.split(",") for line in source.read_text().splitlines() if line]
    header = [name.strip('"') for name in rows[0]]
    groups: dict[str, list[int]] = {}
    for j, name in enumerate(header):
        groups.setdefault(re.sub(r"\[\d+\]$", "", name), []).append(j)
    for base, columns in groups.items():  # elements in their index order
        columns.sort(key=lambda j: int(re.findall(r"\d+", header[j][len(base):] or "0")[-1]))
    lines = [",".join(f'"{name}"' for name in groups)]
    lines += [",".join(" ".join(row[j] for j in columns) for columns in groups.values())
              for row in rows[1:]]
    target.write_text("\n".join(lines) + "\n")


def lay_out(out: Path, tool_version: str, models: list[str] | None = None) -> list[Path]:
    """Writes the folder of every FMU (of `models`, default all) and interface; the
    folders."""
    folders = []
    for variant, fmi_version, platform, tool in VARIANTS:
        for description in sorted((ROOT / "modelDescription" / variant).glob("*.xml")):
            model = description.stem
            if models is not None and model not in models:
                continue
            fmu = ROOT / "dist" / variant / f"{model}.fmu"
            case = defaults_case(model)
            about = ET.parse(description).getroot().get("description", "")
            # The guide: "Check the FMUs with at least one of the available checkers
            # before uploading ... and document this."
            problems = validate_fmu(str(fmu))
            if problems:
                sys.exit(f"compatibility: {fmu}: FMPy's validate_fmu: {'; '.join(problems)}")
            for kind in ("cs", "me"):
                folder = out / "fmus" / fmi_version / kind / platform / tool / tool_version / model
                folder.mkdir(parents=True)
                shutil.copy(fmu, folder / fmu.name)
                copy = write_arrays if variant == "fmi3" else shutil.copy
                copy(case / f"{model}_ref.csv", folder / f"{model}_ref.csv")
                shutil.copy(case / f"{model}_ref.opt", folder / f"{model}_ref.opt")
                for name in (f"{model}_input.csv", f"{model}_in.csv"):
                    if (case / name).is_file():
                        copy(case / name, folder / f"{model}_in.csv")
                for csv in folder.glob("*.csv"):
                    check_csv(csv)
                interface = "Co-Simulation" if kind == "cs" else "Model Exchange"
                (folder / "Readme.txt").write_text(
                    f"{model} {tool_version} (robofmu), FMI {fmi_version}"
                    f"{' scalar-only' if tool.endswith('scalar') else ''} {interface}, "
                    f"{platform}.\n\n{about}.\n\nTested: the FMU simulated with its default "
                    f"parameters, the experiment of {model}_ref.opt and the inputs of "
                    f"{model}_in.csv where present, every signal of {model}_ref.csv within "
                    "the FMI cross-check band. The reference was computed without running "
                    f"the FMU (robofmu, tests/references/{model}/{case.name}): "
                    f"{(case / 'cross-check.txt').read_text().strip()}\n\nThe FMU carries "
                    "this experiment and its validation experiments itself (FMI-LS-REF: "
                    "extra/org.fmi-standard.fmi-ls-ref/, documentation/fmi-ls-ref.html).\n\n"
                    f"Checked with FMPy {fmpy.__version__} (fmpy.validation.validate_fmu, "
                    "the checks of `fmpy validate`: the modelDescription.xml against the "
                    "FMI schema and its rules): no problem.\n")
                folders.append(folder)
    return folders


def _case(folder: Path):
    """The case of `folder` as cosim verify reads it, and its inputs at a time."""
    sys.path.insert(0, str(ROOT))
    from robofmu.verify.case import load_case

    options = argparse.Namespace(reference=None, input=None, step=None, start=None,
                                 tolerance=None, allow_early_end=False)
    case = load_case(folder, options)
    inputs = case.inputs
    names = list(inputs.columns) if inputs is not None else []

    def at(t: float) -> list[float]:
        assert inputs is not None
        return [float(np.interp(t, inputs.time, inputs.columns[n])) for n in names]

    return case, names, at


def _judge(case, rows: np.ndarray) -> str:
    """The verdict of the outputs `rows` (time, then the case's signals, after each
    step), judged from the first step on."""
    from robofmu.verify.compare import judge_all
    from robofmu.verify.simulate import Run

    case.start = float(rows[0, 0])
    run = Run(rows[:, 0], {s: rows[:, j + 1] for j, s in enumerate(case.signals())})
    verdicts, end = judge_all(case, run, "CoSimulation")
    return "passed" if end is None and all(v.passed for v in verdicts) else "failed"


def ecos_verdict(folder: Path) -> str:
    """ecos's verdict on the Co-Simulation case of `folder`: the FMU alone, its inputs
    set before initialization and before each step (linear in time)."""
    from ecospy.EcosSimulation import EcosSimulation
    from ecospy.EcosSimulationStructure import EcosSimulationStructure
    from ecospy.lib import EcosLib

    case, names, at = _case(folder)
    EcosLib.set_log_level("warn")
    structure = EcosSimulationStructure()
    structure.add_model("fmu", str(folder / f"{folder.name}.fmu"))
    steps = round((case.stop - case.start) / case.step)
    rows = np.empty((steps, len(case.signals()) + 1))
    with EcosSimulation(structure=structure, step_size=case.step) as sim:
        for name, value in zip(names, at(case.start) if names else []):
            sim.set_real(f"fmu::{name}", value)
        if not sim.init():
            return "failed (initialization)"
        for k in range(steps):
            for name, value in zip(names, at(case.start + k * case.step) if names else []):
                sim.set_real(f"fmu::{name}", value)
            rows[k, 0] = sim.step(1)
            rows[k, 1:] = [sim.get_real(f"fmu::{s}") for s in case.signals()]
        sim.terminate()
    return _judge(case, rows)


def libcosim_verdict(folder: Path) -> str:
    """libcosim's verdict on the Co-Simulation case of `folder`: the FMU alone, its
    inputs set before each step (linear in time), its outputs after each step, every
    signal judged by the FMI cross-check band."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    case, names, at = _case(folder)
    log_output_level(CosimLogLevel.WARNING)
    execution = CosimExecution.from_step_size(round(case.step * 1e9))
    slave = CosimLocalSlave(fmu_path=str(folder / f"{folder.name}.fmu"), instance_name="fmu")
    if not slave.ptr():  # libcosimpy would pass the NULL slave on and crash the process
        from libcosimpy._internal import get_last_error_message
        return f"refused ({re.sub(r' for FMU .*', '', get_last_error_message())})"
    index = execution.add_local_slave(slave)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    manipulator = CosimManipulator.create_override()
    execution.add_manipulator(manipulator)
    refs = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
    outputs = [refs[name] for name in case.signals()]
    input_refs = [refs[name] for name in names]
    for ref, value in zip(input_refs, at(case.start) if names else []):
        execution.real_initial_value(index, ref, value)
    steps = round((case.stop - case.start) / case.step)
    rows = np.empty((steps, len(outputs) + 1))
    for k in range(steps):
        if names:
            manipulator.slave_real_values(index, input_refs, at(case.start + k * case.step))
        if not execution.step(1):
            return f"failed (step {k} failed)"
        rows[k, 0] = case.start + execution.status().current_time * 1e-9
        rows[k, 1:] = observer.last_real_values(index, outputs)
    return _judge(case, rows)


class Stimuli:
    """The case's inputs as the source FMU of our master (robofmu.master.Master): its
    outputs are the input CSV's columns, linear in time, at the time it has reached."""

    def __init__(self, names: list[str], at, start: float):
        self.names, self.at, self.t = names, at, start

    def get_values(self, names: list[str]) -> list[float]:
        now = dict(zip(self.names, self.at(self.t)))
        return [now[n] for n in names]

    def do_step(self, t: float, h: float) -> None:
        self.t = t + h

    def enter_initialization(self) -> None:
        """Nothing to initialize: the CSV is the whole model."""

    exit_initialization = close = enter_initialization


def master_verdict(folder: Path) -> str:
    """Our master's verdict on the Co-Simulation case of `folder`."""
    return _judge(*master_run(folder))


def master_run(folder: Path):
    """The Co-Simulation case of `folder` run by our master, robofmu.master.Master (the
    native stepping loop of `cosim run`): the FMU with its start values, its inputs from
    the case's CSV held over each step (input_extrapolation "hold", as FMPy applies
    them), every reference signal recorded at each communication point. The case and
    the rows (time, then the signals)."""
    sys.path.insert(0, str(ROOT))
    from robofmu.fmi2 import FmuInstance
    from robofmu.fmi3 import Fmu3Instance
    from robofmu.master import Master
    from robofmu.scenario import Connection, Scenario, Signal

    case, names, at = _case(folder)
    fmu = folder / f"{folder.name}.fmu"
    connections = [Connection(Signal("stimuli", n), Signal("fmu", n)) for n in names]
    scenario = Scenario(
        name="compatibility", fmus={"stimuli": folder, "fmu": fmu},
        order=["stimuli", "fmu"] if names else ["fmu"], start_time=case.start,
        stop_time=case.stop, step_size=case.step,
        parameters={"fmu": dict(case.start_values)}, connections=connections,
        record=[Signal("fmu", s) for s in case.signals()], input_extrapolation="hold")
    fmi3 = "/3.0/" in folder.as_posix()

    def open_fmu(alias, path, s):
        if alias == "stimuli":
            return Stimuli(names, at, s.start_time)
        opened = Fmu3Instance if fmi3 else FmuInstance
        return opened(alias, path, s.start_time, s.stop_time)

    result = Master(scenario, open_fmu=open_fmu, close_fmu=lambda f: f.close()).run()
    rows = np.column_stack([result.time] + [result.columns[f"fmu.{s}"]
                                            for s in case.signals()])
    return case, rows


def container_verdict(folder: Path) -> str:
    """The container runtime's verdict on the Co-Simulation case of `folder`: the FMU
    alone inside a container FMU of fmu-manipulation-toolbox (its compiled runtime loads
    and steps the FMU; its inputs and the reference signals are the container's inputs
    and outputs under the same names, its start values the container's), the container
    run by `cosim verify` (FMPy) against the same case."""
    import tempfile

    from fmu_manipulation_toolbox.container import FMUContainer
    from fmu_manipulation_toolbox.operations import FMUError

    case, names, _ = _case(folder)
    model = folder.name
    fmi_version = 3 if "/3.0/" in folder.as_posix() else 2

    def whole(names: list[str]) -> list[str]:
        """The variables of `names`: an FMI 3.0 array (robofmu, not robofmu-scalar) once
        for its elements x[i], the toolbox's ports being whole variables."""
        if fmi_version == 2 or "/robofmu-scalar/" in folder.as_posix():
            return names
        return list(dict.fromkeys(re.sub(r"\[\d+\]$", "", n) for n in names))

    with tempfile.TemporaryDirectory(prefix="compatibility-container-") as scratch:
        work = Path(scratch)
        shutil.copy(folder / f"{model}.fmu", work / f"{model}.fmu")
        container = FMUContainer(f"{model}_container", work, fmi_version=fmi_version)
        container.get_fmu(f"{model}.fmu")
        try:
            for name in whole(names):
                container.add_input(name, f"{model}.fmu", name)
            for signal in whole(case.signals()):
                container.add_output(f"{model}.fmu", signal, signal)
        except FMUError as refusal:  # e.g. an array sized by a structural parameter
            return f"refused ({refusal})"
        for name, value in case.start_values.items():
            text = str(value).lower() if isinstance(value, bool) else repr(value)
            container.add_start_value(f"{model}.fmu", name, text)
        container.add_implicit_rule(auto_input=False, auto_output=False, auto_link=False)
        container.start_time, container.stop_time = case.start, case.stop
        container.make_fmu(f"{model}.fmu", step_size=case.step, sequential=True)
        case_copy = work / "case" / model
        shutil.copytree(folder, case_copy, ignore=shutil.ignore_patterns("*.fmu"))
        done = subprocess.run([sys.executable, "-m", "robofmu.verify", str(work / f"{model}.fmu"),
                               str(case_copy), "--interface", "cs", "--out", str(work / "out"),
                               *DEBUG],
                              capture_output=True, text=True, cwd=ROOT)
    if done.returncode == 0:
        return "passed"
    said = (done.stdout + done.stderr).strip().splitlines()
    return f"failed ({said[-1] if said else f'exit status {done.returncode}'})"


DEBUG = sys.argv[3:]
IMPORTERS = {"libcosim": libcosim_verdict, "ecos": ecos_verdict, "master": master_verdict,
             "container": container_verdict}


def verdict_of(importer: str, folder: Path) -> str:
    """An importer's verdict in a child process: a crash of its library costs this case
    only."""
    done = subprocess.run([sys.executable, __file__, f"--{importer}", str(folder)],
                          capture_output=True, text=True)
    said = done.stdout.strip().splitlines()
    if done.returncode != 0 or not said:
        return f"failed (exit status {done.returncode})"
    return said[-1]


def importers(tool_version: str) -> dict[str, str]:
    """Each importer (its column) with its version, as the README names it."""
    container = importlib.metadata.version("fmu-manipulation-toolbox")
    return {
        "cosim": f"cosim {tool_version} (robofmu's `cosim verify`) on FMPy {fmpy.__version__}",
        "master": f"cosim {tool_version} master (robofmu.master, the native stepping loop of "
                  "`cosim run`)",
        "container": f"the container runtime of fmu-manipulation-toolbox {container} (the FMU "
                     f"alone in a container FMU, run by FMPy {fmpy.__version__})",
        "libcosim": f"libcosim (libcosimpy {importlib.metadata.version('libcosimpy')})",
        "ecos": f"ecos (ecospy {importlib.metadata.version('ecospy')})",
    }


def runs(label: str) -> list[str]:
    """The importers that run the case `label` (FMI version/interface/platform/tool/...):
    every case in cosim verify; the Co-Simulation ones in our master, the container
    and libcosim (which refuses FMI 3.0); ecos the FMI 2.0 and scalar-only FMI 3.0 ones."""
    if not label.split("/")[1] == "cs":
        return []
    scalars = label.startswith("2.0/") or "/robofmu-scalar/" in label
    return ["master", "container", "libcosim"] + (["ecos"] if scalars else [])


def known_refusal(importer: str, label: str, verdict: str) -> bool:
    """A refusal LIMITS explains: libcosim loads no FMI 3.0 FMU; the toolbox's container
    takes no port sized by a structural parameter (the FMI 3.0 PID's arrays)."""
    return label.startswith("3.0/") and (
        (importer == "libcosim" and "Unsupported FMI version" in verdict)
        or (importer == "container" and "structuralParameter" in verdict))


LIMITS = """Each importer runs the cases it can:

- cosim (FMPy): every case, Co-Simulation and Model Exchange.
- Our master, the container runtime, libcosim and ecos: Co-Simulation only (the master
  and libcosim import co-simulation FMUs only; the container FMU is one).
- libcosim loads FMI 1.0 and 2.0 FMUs only: it refuses every FMI 3.0 FMU ("Unsupported
  FMI version", its `cosim_local_slave_create` returns no slave; libcosimpy 0.0.6 does
  not check that and crashes the process in `cosim_execution_add_slave` when it is added
  to an execution, so it is not added). It refuses a third-party FMI 3.0 FMU alike.
- The container runtime of fmu-manipulation-toolbox 2.0 refuses the FMI 3.0 PID with
  arrays: its container builder takes no port whose size is a structural parameter, and
  the PID's arrays are sized by `nChannels`.
- ecos: not the FMI 3.0 FMUs with arrays (it offers an array as one scalar and reads
  one element of it); their scalar-only builds (`robofmu-scalar`) run.
- fmusim (Reference-FMUs' simulator) is not among them: no package that the release's
  machines reach (PyPI, Debian, crates.io) ships it, its source or a way to build it
  (docs/verify.md, "Importers left out").
"""


def columns(tool_version: str) -> dict[str, str]:
    """Each importer other than cosim as the results page's column names it, with its
    version."""
    return {
        "master": f"our master (cosim {tool_version})",
        "container": "container runtime (fmu-manipulation-toolbox "
                     f"{importlib.metadata.version('fmu-manipulation-toolbox')})",
        "libcosim": f"libcosim (libcosimpy {importlib.metadata.version('libcosimpy')})",
        "ecos": f"ecos (ecospy {importlib.metadata.version('ecospy')})",
    }


def results_page(out: Path, tool_version: str, verdicts: dict[str, str],
                 summaries: dict[str, str], others: list[tuple[Path, str, str]]) -> bytes:
    """The results page of the compatibility folder: cosim verify's cases (`verdicts`
    and `summaries` by case label, as its run printed them; its results under
    out/results/) and each other importer's verdict on a case folder (`others`), one
    matrix FMU x importer x platform; every file a link relative to out/index.html."""
    sys.path.insert(0, str(ROOT))
    from robofmu.verify.page import Entry, page
    from robofmu.verify.tree import find_cases, page_entry

    entries = []
    for case in find_cases(out / "fmus"):
        label = case.label()
        written = case.results(out)
        files = sorted(p for p in written.iterdir() if p.is_file()) if written.is_dir() else []
        entries.append(page_entry(case, out, verdicts.get(label, "not run"),
                                  summaries.get(label, f"{label}: not run"), files))
    named, short = importers(tool_version), columns(tool_version)
    for folder, importer, said in others:
        version, kind, platform, tool, release, model = folder.parts[-6:]
        label = "/".join(folder.parts[-6:])
        entries.append(Entry(
            f"{model}.fmu", version, kind, platform, short[importer], label,
            said.split(" (")[0], f"{label}: imported and simulated with {named[importer]}, "
            f"Co-Simulation: {said}.", folder,
            sorted(p for p in folder.iterdir() if p.is_file()), tool=f"{tool} {release}",
            how=f"Case {label}: the FMU alone, the experiment of its _ref.opt, the inputs "
                "of its _in.csv where present, every signal of its _ref.csv judged by "
                "cosim verify's rule (the FMI cross-check band); its Readme.txt records "
                "the verdict."))
    note = ("An empty cell: the importer does not run that case (Model Exchange runs in "
            "cosim only; ecos does not run the FMI 3.0 FMUs with arrays, their "
            "scalar-only builds it does); README.md beside this page says why.")
    return page(f"robofmu {tool_version}: compatibility information", entries,
                out / "index.html", note)


def main() -> int:
    if len(sys.argv) >= 3 and sys.argv[1].removeprefix("--") in IMPORTERS:
        print(IMPORTERS[sys.argv[1].removeprefix("--")](Path(sys.argv[2])))
        return 0
    if len(sys.argv) != 2:
        sys.exit("usage: python scripts/compatibility.py OUT")
    out = Path(sys.argv[1])
    if out.exists() and any(out.iterdir()):
        sys.exit(f"compatibility: {out} is not empty; name a new or empty folder")
    tool_version = version()
    folders = lay_out(out, tool_version)
    named = importers(tool_version)
    jobs = min(4, os.cpu_count() or 1)  # each case, and each importer's run, a process
    done = subprocess.run([sys.executable, "-m", "robofmu.verify", str(out / "fmus"),
                           "--out", str(out), "--html", str(out / "index.html"),
                           "--jobs", str(jobs)], capture_output=True, text=True)
    verdicts, summaries = {}, {}
    for line in done.stdout.splitlines():
        found = re.match(r"\[\d+/\d+\] (\w+)\s+(\S+ \S+ \S+ against (\S+):.*)", line)
        if found:
            verdicts[found.group(3)] = found.group(1).lower()
            summaries[found.group(3)] = found.group(2)
    if not verdicts:
        sys.stderr.write(done.stdout + done.stderr)
        return 1
    with ThreadPoolExecutor(jobs) as pool:
        running = {(folder, importer): pool.submit(verdict_of, importer, folder)
                   for folder in folders for importer in runs("/".join(folder.parts[-6:]))}
    rows, failed, entries = [], False, []
    for folder in folders:
        label = "/".join(folder.parts[-6:])
        verdict = verdicts.get(label, "not run")
        parts = label.split("/")
        results = "/".join(["results", *parts[:3], "cosim", tool_version, *parts[3:]])
        lines = [f"Imported and simulated with {named['cosim']}: {verdict} ({results}/ and "
                 "index.html of the compatibility folder)."]
        by = {importer: running[folder, importer].result() for importer in runs(label)}
        for importer, said in by.items():
            lines.append(f"Imported and simulated with {named[importer]}, Co-Simulation: "
                         f"{said}.")
        # Every verdict must be "passed" but the known refusals (LIMITS).
        failed |= verdict != "passed" or any(
            v != "passed" and not known_refusal(i, label, v) for i, v in by.items())
        with (folder / "Readme.txt").open("a") as f:
            f.write("\n" + "\n".join(lines) + "\n")
        entries += [(folder, importer, said) for importer, said in by.items()]
        cells = [by.get(i, "not run").split(" (")[0] for i in named if i != "cosim"]
        rows.append(f"| {label} | {verdict} | " + " | ".join(cells) + " |")
    listed = "\n".join(f"- {name}" for name in named.values())
    (out / "README.md").write_text(
        f"# robofmu {tool_version}: compatibility information\n\nEvery FMU of robofmu "
        f"{tool_version} in `fmus/` with its reference (`_ref.csv`, `_ref.opt`, `_in.csv`) "
        "and `Readme.txt`, in the layout of the FMI cross-check. Importers that ran "
        f"them (scripts/compatibility.py, at release):\n\n{listed}\n\n{LIMITS}\n"
        "Each case's `Readme.txt` gives each importer's verdict with its reason. The results "
        "page of cosim: `index.html`; its results: `results/`, `junit.xml`.\n\n"
        "| FMU | cosim (FMPy) | our master | container | libcosim | ecos |\n"
        "|---|---|---|---|---|---|\n" + "\n".join(rows) + "\n")
    (out / "index.html").write_bytes(results_page(out, tool_version, verdicts, summaries,
                                                  entries))
    print(done.stdout.splitlines()[-1])
    return 1 if failed or done.returncode != 0 else 0


if __name__ == "__main__":
    sys.exit(main())
