"""One version everywhere, and the release folder that docs/release.md lists.

Truths: the workspace version is read from Cargo.toml with tomllib; each FMU's version
is read from its modelDescription by FMPy (a second reader besides cosim's own), the
checked-in copies under modelDescription/ with ElementTree; the release folder's files
are those scripts/release.sh writes into a temporary folder, compared with the table of
docs/release.md (names exactly, sizes within 25 %: the table is a measurement, to be
rewritten when the FMUs change size, e.g. with more platforms), and its compatibility
folder against the rules of the FMI website's contribution guide (CONTRIBUTING.md of
modelica/fmi-standard.org, "Compatibility information"), read from fmpy's
read_model_description for the inputs."""

import re
import subprocess
import tomllib
from pathlib import Path
from xml.etree import ElementTree

import fmpy
from fmpy import read_model_description
from page_matrix import check_in_browser, unresolved
from page_matrix import matrix as page_matrix

ROOT = Path(__file__).resolve().parents[2]
CONTAINER_REFUSED = ("refused (Port 'setpoint' depends on structuralParameter '90' which is "
                     "not supported)")
ROW = re.compile(r"^\| `([^`]+)` \| (\d+) \|", re.M)


def workspace_version() -> str:
    with (ROOT / "Cargo.toml").open("rb") as f:
        return tomllib.load(f)["workspace"]["package"]["version"]


def test_one_version_in_every_crate_fmu_command_and_the_changelog():
    version = workspace_version()
    manifests = [ROOT / "Cargo.toml", *ROOT.glob("crates/**/Cargo.toml"),
                 *ROOT.glob("fmus/*/Cargo.toml")]
    assert len(manifests) >= 13
    for manifest in manifests:
        with manifest.open("rb") as f:
            assert tomllib.load(f)["package"]["version"] == {"workspace": True}, manifest
    said = subprocess.run([str(ROOT / ".venv" / "bin" / "cosim"), "--version"],
                          capture_output=True, text=True, check=True).stdout
    assert said == f"cosim {version}\n"
    said = subprocess.run([str(ROOT / "target" / "release" / "robofmu"), "--version"],
                          capture_output=True, text=True, check=True).stdout
    assert said == f"robofmu {version}\n"
    copies = sorted((ROOT / "modelDescription").rglob("*.xml"))
    fmus = sorted((ROOT / "dist").rglob("*.fmu"))
    assert len(copies) == 12 and len(fmus) >= 12
    for copy in copies:
        root = ElementTree.parse(copy).getroot()
        assert root.get("version") == version, copy
        assert root.get("generationTool") == f"robofmu {version}", copy
    for fmu in fmus:
        md = read_model_description(str(fmu))
        assert (md.version, md.generationTool) == (version, f"robofmu {version}"), fmu
    headings = re.findall(r"^## (\S+)", (ROOT / "CHANGELOG.md").read_text(), re.M)
    assert version in headings


def test_release_folder_holds_what_the_docs_list(tmp_path):
    out = tmp_path / "release"
    run = subprocess.run(["bash", str(ROOT / "scripts" / "release.sh"), "--out", str(out)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-3000:]
    every = {p.relative_to(out).as_posix(): p.stat().st_size
             for p in out.rglob("*") if p.is_file()}
    # The compatibility folder (every FMU twice with its reference, results and plots:
    # hundreds of files) is listed by its top files; its layout is checked below.
    written = {n: s for n, s in every.items()
               if not n.startswith("compatibility/") or n.count("/") == 1}
    listed = {name: int(size) for name, size in
              ROW.findall((ROOT / "docs" / "release.md").read_text())}
    table = "\n".join(f"| `{n}` | {s} |" for n, s in sorted(written.items()))
    assert written.keys() == listed.keys(), f"docs/release.md's table; now:\n{table}"
    # The version's CHANGELOG section grows with every change until the release: its size
    # is listed as of the last rewrite of the table, not checked.
    off = {n: (listed[n], s) for n, s in written.items()
           if not n.startswith("CHANGELOG-") and not 0.75 <= s / listed[n] <= 1.25}
    assert not off, f"sizes (docs, now) {off}; rewrite docs/release.md's table:\n{table}"
    # The sums check, and the CHANGELOG section is the version's.
    subprocess.run(["sha256sum", "--check", "--quiet", "SHA256SUMS"], cwd=out, check=True)
    version = workspace_version()
    section = (out / f"CHANGELOG-{version}.md").read_text()
    assert section.startswith(f"## {version}") and "\n## 0." not in section[3:]
    check_compatibility(out / "compatibility", version)


def check_compatibility(folder: Path, version: str) -> None:
    """The layout the FMI tools list asks for (modelica/fmi-standard.org CONTRIBUTING.md,
    "Compatibility information"): per FMU its .fmu, _ref.csv (at most 10 variables, at
    most 1 MB), _ref.opt, _in.csv for a model with inputs, a ReadMe; the importer that ran
    it with its version and verdict (FMPy every case, libcosim the FMI 2.0 Co-Simulation
    ones, ecos those and the scalar-only FMI 3.0 ones); every FMU of the release, both
    interfaces."""
    fmus = sorted(folder.glob("fmus/*/*/*/*/*/*/*.fmu"))
    assert len(fmus) == 24  # 12 FMUs x Co-Simulation and Model Exchange
    for fmu in fmus:
        model, case = fmu.stem, fmu.parent
        reference = case / f"{model}_ref.csv"
        assert reference.stat().st_size <= 1_000_000
        assert len(reference.read_text().splitlines()[0].split(",")) - 1 <= 10
        assert (case / f"{model}_ref.opt").is_file()
        variables = read_model_description(str(fmu)).modelVariables
        inputs = [v for v in variables if v.causality == "input"]
        assert (case / f"{model}_in.csv").is_file() == bool(inputs)
        # "All variable names are exactly the same as defined in the modelDescription.xml"
        # (an FMI 3.0 array is one column, its elements separated by spaces).
        names = {v.name for v in variables}
        for written in case.glob("*.csv"):
            header = written.read_text().splitlines()[0].split(",")
            assert {n.strip('"') for n in header[1:]} <= names, written
        readme = (case / "Readme.txt").read_text()
        assert f"on FMPy {fmpy.__version__}: passed" in readme, readme
        assert f"Checked with FMPy {fmpy.__version__}" in readme, readme
        # Co-Simulation: our master and the container runtime every case, libcosim the
        # FMI 2.0 ones (it refuses FMI 3.0, saying why), ecos those and the scalar-only
        # FMI 3.0 ones.
        path = case.as_posix()
        cs = "/cs/" in path
        fmi2 = "/2.0/cs/" in path
        ecos = fmi2 or (cs and "/robofmu-scalar/" in path)
        assert ("master (robofmu.master, the native stepping loop of `cosim run`), "
                "Co-Simulation: passed." in readme) == cs, readme
        # The container refuses the FMI 3.0 PID's arrays, sized by a structural parameter.
        resizable = model == "PID" and "/3.0/cs/" in path and "/robofmu/" in path
        assert ("(the FMU alone in a container FMU, run by FMPy "
                f"{fmpy.__version__}), Co-Simulation: passed." in readme) == (
                    cs and not resizable), readme
        assert (f"Co-Simulation: {CONTAINER_REFUSED}." in readme) == resizable, readme
        assert ("(libcosimpy 0.0.6), Co-Simulation: passed." in readme) == fmi2, readme
        assert ("(libcosimpy 0.0.6), Co-Simulation: refused (Unsupported feature: "
                "Unsupported FMI version)." in readme) == (cs and not fmi2), readme
        assert ("(ecospy 0.7.2), Co-Simulation: passed." in readme) == ecos, readme
    summary = (folder / "README.md").read_text()
    rows = re.findall(r"^\| (\S+) \| (\w+) \| ([\w ]+) \| ([\w ]+) \| ([\w ]+) \| ([\w ]+) \|$",
                      summary, re.M)
    assert len(rows) == 24 and all(row[1] == "passed" for row in rows)
    counts = [sum(row[k] == "passed" for row in rows) for k in range(2, 6)]
    assert counts == [12, 11, 4, 8]  # master, container, libcosim, ecos
    assert sum(row[4] == "refused" for row in rows) == 8
    assert sum(row[3] == "refused" for row in rows) == 1
    assert all(v in ("passed", "refused", "not run") for row in rows for v in row[2:])
    assert f"cosim {version}" in summary and "fmu-manipulation-toolbox 2.0" in summary
    assert "fmusim" in summary  # why it is not among the importers
    # The results page: the same verdicts as README.md's table (the truth here, written
    # from each importer's run), one row per FMU, FMI version, exporting tool and
    # platform, one column per importer with its version; every link resolves.
    page = folder / "index.html"
    assert unresolved(page) == []
    check_in_browser(page, ROOT / "results" / "verify-page" / "compatibility.png")
    matrix = page_matrix(page)
    assert len(matrix) == 12 and all(len(cells) == 5 for cells in matrix.values())
    named = dict(zip(["cosim", "master", "container", "libcosim", "ecos"], next(
        iter(matrix.values()))))
    assert named["libcosim"] == "libcosim (libcosimpy 0.0.6)"
    assert named["ecos"] == "ecos (ecospy 0.7.2)"
    for label, *verdicts in rows:
        fmi, kind, plat, tool, release, model = label.split("/")
        cells = matrix[f"{model}.fmu (FMI {fmi}, {tool} {release}), {plat}"]
        lines = {k: [line for line in cells[named[k]].splitlines()
                     if line.startswith(f"{kind} ")] for k in named}
        assert lines["cosim"] == [f"{kind} {verdicts[0]}"], (label, cells)
        for k, verdict in zip(list(named)[1:], verdicts[1:]):
            if verdict == "not run":
                assert lines[k] == [], (label, k, cells)
            elif verdict == "refused":  # with its reason
                reason = (CONTAINER_REFUSED if k == "container" else
                          "refused (Unsupported feature: Unsupported FMI version)")
                assert lines[k] == [f"{kind} {reason}"], (label, k, cells)
            else:
                assert lines[k] == [f"{kind} {verdict}"], (label, k, cells)
