"""``cosim verify TREE``: every case of an FMI cross-check tree.

A case is a folder ``<FMI version>/<cs|me>/<platform>/<tool>/<version>/<Model>/`` (under
``fmus/``, anywhere below TREE) holding ``<Model>.fmu``. Each case whose FMU has a binary
for this machine is run as ``cosim verify`` runs one (the folder's interface, its
``_ref.opt`` experiment, its ``_in.csv`` inputs, the FMI cross-check band for every
signal unless --tolerance says otherwise); one line per case as it ends, then a summary.
The results go to ``OUT/results/<FMI version>/<cs|me>/<platform>/cosim/<our version>/
<tool>/<version>/<Model>/`` as the cross-check rules ask an importing tool to submit
them: a ``passed``, ``failed`` or ``rejected`` marker, ``README.md`` (how it was run and
the verdicts), ``<Model>_out.csv`` (the result), with ``verify.json`` and the plots
beside them; one JUnit file (``OUT/junit.xml`` or --junit) holds one test suite a case.
"""

from __future__ import annotations

import os
import platform
import sys
import time
import xml.etree.ElementTree as ET
import zipfile
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import fmpy

from .. import bundle
from . import junit
from .errors import COMMAND_LINE, VerifyError
from .files import write_all
from .page import Entry, page
from .runner import CaseResult, verify_case
from .simulate import INTERFACE_NAMES

TOOL = "cosim"
FMI_VERSIONS = ("1.0", "2.0", "3.0")
TYPES = tuple(INTERFACE_NAMES)  # cs, me


def tool_version() -> str:
    """The importing tool's version (the results' {Importing_Tool_Version}): cosim's own,
    the workspace's in a checkout or the installed wheel's (robofmu.bundle.version)."""
    return bundle.version()


def platforms() -> tuple[tuple[str, ...], str, str]:
    """This machine: its platform folder names, and the binaries folders of an FMI 2.0
    and an FMI 3.0 FMU (the standards' names)."""
    system = {"linux": "linux", "darwin": "darwin", "win32": "win"}.get(sys.platform, sys.platform)
    arm = platform.machine().lower() in ("arm64", "aarch64")
    fmi2 = {"linux": "linux64", "darwin": "darwin64", "win": "win64"}.get(system, system)
    fmi3 = f"{'aarch64' if arm else 'x86_64'}-{'windows' if system == 'win' else system}"
    return (fmi2, fmi3), fmi2, fmi3


@dataclass
class TreeCase:
    folder: Path
    fmi_version: str
    kind: str
    platform: str
    tool: str
    version: str
    model: str

    @property
    def fmu(self) -> Path:
        return self.folder / f"{self.model}.fmu"

    def label(self) -> str:
        return "/".join([self.fmi_version, self.kind, self.platform, self.tool,
                         self.version, self.model])

    def results(self, out: Path) -> Path:
        return (out / "results" / self.fmi_version / self.kind / self.platform / TOOL /
                tool_version() / self.tool / self.version / self.model)


def find_cases(tree: Path) -> list[TreeCase]:
    """Every ``<Model>/<Model>.fmu`` below `tree` six folders below an FMI version folder
    (the folders above `tree` count: TREE may be any folder of the layout)."""
    cases = []
    for fmu in sorted(tree.rglob("*.fmu")):
        parts = fmu.parent.resolve().parts
        if len(parts) < 6 or fmu.stem != parts[-1]:
            continue
        version, kind, plat, tool, tool_ver, model = parts[-6:]
        if version in FMI_VERSIONS and kind in TYPES:
            cases.append(TreeCase(fmu.parent, version, kind, plat, tool, tool_ver, model))
    return cases


def skip_reason(case: TreeCase, interface: str | None) -> str | None:
    """Why the case is not run here (another interface than --interface asks for, a
    platform or FMI version this machine cannot run), or None."""
    if interface is not None and case.kind != interface:
        return f"interface {case.kind} (--interface {interface})"
    names, fmi2, fmi3 = platforms()
    if case.fmi_version == "1.0":
        return "FMI 1.0 (cosim verify runs FMI 2.0 and 3.0)"
    if case.platform not in names:
        return f"platform {case.platform} (this machine: {' or '.join(names)})"
    binaries = f"binaries/{fmi2 if case.fmi_version == '2.0' else fmi3}/"
    try:
        with zipfile.ZipFile(case.fmu) as archive:
            if not any(n.startswith(binaries) and not n.endswith("/")
                       for n in archive.namelist()):
                return f"no {binaries} in the FMU"
    except (OSError, zipfile.BadZipFile) as e:
        return f"the FMU cannot be opened ({e})"
    return None


def _readme(case: TreeCase, status: str, lines: list[str], summary: str) -> bytes:
    """The README.md the rules ask for: how the case was run, and why it did not pass;
    file names relative to the case's folder."""
    summary = summary.replace(f"{case.folder}{os.sep}", "")
    head = (f"# {case.model}: {status}\n\nImported with {TOOL} {tool_version()} (`cosim verify`, "
            f"the robofmu harness, on FMPy {_fmpy_version()}), FMI {case.fmi_version} "
            f"{INTERFACE_NAMES[case.kind]}, {case.platform}.\n\n")
    if status == "rejected":
        return (head + "Not simulated: the case's files do not fit the FMU.\n\n"
                f"    {summary}\n").encode()
    how = (f"The FMU was simulated with its default parameters, the experiment of "
           f"`{case.model}_ref.opt` and the inputs of `{case.model}_in.csv` where present, "
           f"and each signal of `{case.model}_ref.csv` compared with the result "
           f"(`{case.model}_out.csv`), each within the tolerance its line below names (the "
           "FMI cross-check band: at most 10 % of the samples outside a band of 10 % of "
           "the signal's range; docs/verify.md of robofmu).\n\n")
    verdicts = "".join(f"    {line}\n" for line in lines)
    return (head + how + f"{summary}\n\n" + verdicts).encode()


def _fmpy_version() -> str:
    return fmpy.__version__


def _run_one(case: TreeCase, args) -> tuple[str, list[str], str, dict, bytes]:
    """(status, lines, summary, files, JUnit suite) of one case; a case whose files
    are wrong is rejected with the reason."""
    out = case.results(args.out)
    name = case.label()
    try:
        result: CaseResult = verify_case(case.fmu, case.folder, args, case.kind, out, name,
                                         f"{case.model}_out.csv",
                                         plot_all=args.html is not None)
        status, lines, summary, files, suite = (result.status, result.lines, result.summary,
                                                dict(result.files), result.suite)
    except VerifyError as e:
        status, lines, summary, files = "rejected", [], f"{name}: rejected: {e}", {}
        interface = INTERFACE_NAMES[case.kind]
        suite = ET.tostring(junit.error_suite(f"{case.fmu.name} ({interface}) against {name}",
                                              f"{case.model}.{interface}", str(e), "rejected"))
    files[out / status] = b""
    files[out / "README.md"] = _readme(case, status, lines, summary)
    return status, lines, summary, files, suite


def _clear_stale(case: TreeCase, out: Path, files: dict) -> None:
    """Removes what an earlier run wrote in the case's results folder and this one does
    not (its marker, plots, result): only the names verify writes there."""
    folder = case.results(out)
    if not folder.is_dir():
        return
    names = ["passed", "failed", "rejected", "verify.json", f"{case.model}_out.csv"]
    for path in [folder / n for n in names] + sorted(folder.glob("*.png")):
        if path not in files and path.is_file():
            path.unlink()


def importer_name() -> str:
    """This importer as the results page names it: cosim and the FMPy it runs on."""
    return f"{TOOL} {tool_version()} (FMPy {_fmpy_version()})"


def page_entry(case: TreeCase, out: Path, status: str, summary: str,
               written: list[Path]) -> Entry:
    """The results page's entry of `case`, verified into `out` with the verdict `status`
    and `summary`: the case's files and `written`, its results."""
    inputs = sorted(p for p in case.folder.iterdir() if p.is_file())
    return Entry(case.fmu.name, case.fmi_version, case.kind, case.platform, importer_name(),
                 case.label(), status, summary, case.results(out), inputs + sorted(written),
                 tool=f"{case.tool} {case.version}")


def verify_tree(args) -> int:
    tree = args.fmu
    if args.case is not None or args.reference is not None or args.input is not None:
        raise VerifyError(COMMAND_LINE, "CASE/--reference/--input", "a tree gives each "
                          "case its own files", "leave them out when FMU|TREE is a folder")
    cases = find_cases(tree)
    if not cases:
        raise VerifyError(tree, "TREE", "holds no case <FMI version>/<cs|me>/<platform>/"
                          "<tool>/<version>/<Model>/<Model>.fmu", "give an FMI cross-check "
                          "tree (its fmus/ folder or a folder above it)")
    runnable = [(c, skip_reason(c, args.interface)) for c in cases]
    todo = [c for c, why in runnable if why is None]
    skipped = [(c, why) for c, why in runnable if why is not None]
    if not todo:  # a CI job that ran nothing must not pass
        case, why = skipped[0]
        raise VerifyError(tree, "TREE", f"none of its {len(cases)} cases runs here "
                          f"({case.label()}: {why}, ...)", "give a tree with cases for this "
                          "platform (or leave out --interface)")
    jobs = min(args.jobs, max(1, len(todo)))
    started = time.perf_counter()
    suites, counts = {}, {"passed": 0, "failed": 0, "rejected": 0}
    entries: list[Entry] = []
    print(f"{tree}: {len(cases)} cases, {len(todo)} to run here ({jobs} at once), "
          f"{len(skipped)} skipped", flush=True)

    def finish(k, case, outcome):
        status, lines, summary, files, suite = outcome
        try:
            _clear_stale(case, args.out, files)
            write_all(files)
        except OSError as e:
            raise VerifyError(e.filename or args.out, "--out", f"cannot be written "
                              f"({e.strerror})", "give a writable folder") from None
        counts[status] += 1
        suites[case.label()] = suite
        entries.append(page_entry(case, args.out, status, summary, list(files)))
        print(f"[{k}/{len(todo)}] {status.upper():8} {summary}", flush=True)
        for line in lines:
            if not line.startswith("PASS"):
                print(f"    {line}", flush=True)

    if jobs == 1:
        for k, case in enumerate(todo, 1):
            finish(k, case, _run_one(case, args))
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            futures = [(case, pool.submit(_run_one, case, args)) for case in todo]
            for k, (case, future) in enumerate(futures, 1):
                finish(k, case, future.result())
    for case, why in skipped:
        print(f"SKIPPED  {case.label()}: {why}")
    junit_path = args.junit or args.out / "junit.xml"
    ordered = [ET.fromstring(suites[c.label()]) for c in todo]
    try:
        write_all({junit_path: junit.document(ordered, time.perf_counter() - started)})
    except OSError as e:
        raise VerifyError(e.filename or junit_path, "--junit", f"cannot be written "
                          f"({e.strerror})", "give a writable path") from None
    if args.html is not None:
        try:
            write_all({args.html: page(f"cosim verify {tree}", entries, args.html)})
        except OSError as e:
            raise VerifyError(e.filename or args.html, "--html", f"cannot be written "
                              f"({e.strerror})", "give a writable path") from None
    print(f"{tree}: {counts['passed']} passed, {counts['failed']} failed, "
          f"{counts['rejected']} rejected, {len(skipped)} skipped of {len(cases)} cases "
          f"in {time.perf_counter() - started:.1f} s -> {args.out / 'results'}, {junit_path}"
          + ("" if args.html is None else f", {args.html}"))
    return 0 if counts["failed"] == counts["rejected"] == 0 else 1
