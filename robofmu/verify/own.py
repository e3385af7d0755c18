"""``cosim verify FMU`` without a case: the experiments the FMU carries itself (the
layered standard FMI-LS-REF 1.0.0-alpha.1). The manifest
``extra/org.fmi-standard.fmi-ls-ref/fmi-ls-manifest.xml`` lists experiments files
(MA-HS-Experiments: ``<Experiment>`` with ``<TransientSimulation startTime stopTime
stepSize>``, ``<Parameters>`` (SSP parameter set), ``<Stimuli>``, ``<References>``);
every experiment runs as a case. A ``result`` CSV that no experiment names (as
Reference-FMUs 0.0.41 ship) is the reference of the FMU's DefaultExperiment. Each file
is read from the archive in memory, checked first against the SHA-256 the manifest gives
(annotation ``org.robofmu.checksum``); tolerances and event times come from the
experiment's annotation ``org.robofmu.verify``, else the cross-check band. A broken
archive is bad input (VerifyError, exit 2). docs/verify.md."""

from __future__ import annotations

import hashlib
import posixpath
import re
import xml.etree.ElementTree as ET
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

from . import casefile, tolerance
from .case import DEFAULT_REL_TOL, Case, apply_options, check_case
from .errors import VerifyError
from .table import Table, read_table

FOLDER = "extra/org.fmi-standard.fmi-ls-ref"
MANIFEST = f"{FOLDER}/fmi-ls-manifest.xml"
CHECKSUM = "org.robofmu.checksum"
VERIFY = "org.robofmu.verify"
ALGORITHMS = {"SHA-256": "sha256", "SHA3-256": "sha3_256"}
ANALYSES = ("SteadyState", "ParameterOptimization", "SetPointOptimization",
            "SensitivityAnalysis", "TrajectoryOptimization", "Linearization")
REPACKAGE = "repackage the FMU (its manifest and files must agree)"


def _local(tag: str) -> str:
    """An element's name without its namespace."""
    return tag.rsplit("}", 1)[-1]


def _children(node: ET.Element, name: str) -> list[ET.Element]:
    return [c for c in node if _local(c.tag) == name]


def _annotations(node: ET.Element, kind: str) -> list[ET.Element]:
    """The elements inside `node`'s <Annotations><Annotation type=kind>."""
    return [e for a in _children(node, "Annotations") for b in _children(a, "Annotation")
            if b.get("type") == kind for e in b]


@dataclass
class Archive:
    """The FMU's entries and the checksums its manifest gives them."""

    fmu: Path
    entries: dict[str, bytes]
    checksums: dict[str, tuple[str, str]] = field(default_factory=dict)

    def label(self, path: str) -> str:
        return f"{self.fmu}!/{path}"

    def read(self, path: str, listed_by: str) -> bytes:
        if path not in self.entries:
            raise VerifyError(self.label(path), "", f"is missing from the archive ({listed_by} "
                              "names it)", f"{REPACKAGE}, or remove the entry that names it")
        data = self.entries[path]
        if path in self.checksums:
            algorithm, expected = self.checksums[path]
            actual = hashlib.new(ALGORITHMS[algorithm], data).hexdigest()
            if actual != expected.lower():
                raise VerifyError(self.label(path), "", f"its {algorithm} {actual[:16]}... is "
                                  f"not the manifest's {expected[:16]}... (the file was "
                                  "changed after packaging)", REPACKAGE)
        return data

    def resolve(self, base: str, source: str, where: str) -> str:
        """The archive path of `source`, relative to the file `base`."""
        if re.match(r"^[A-Za-z][A-Za-z0-9+.-]*:", source) or source.startswith("/"):
            raise VerifyError(self.label(base), where, f"source '{source}' is not a relative "
                              "path inside the FMU", "name a file of the archive")
        path = posixpath.normpath(posixpath.join(posixpath.dirname(base), source))
        if path.startswith("../"):
            raise VerifyError(self.label(base), where, f"source '{source}' points outside "
                              "the FMU", "name a file of the archive")
        return path


def open_archive(fmu: Path) -> Archive:
    try:
        with zipfile.ZipFile(fmu) as z:
            entries = {i.filename: z.read(i) for i in z.infolist() if not i.is_dir()}
    except (OSError, zipfile.BadZipFile) as e:
        raise VerifyError(fmu, "", f"cannot be read as a zip archive ({e})",
                          "give an FMU") from None
    if MANIFEST not in entries:
        raise VerifyError(fmu, MANIFEST, "the FMU carries no experiments (no FMI-LS-REF "
                          "manifest)", "give a case folder or --reference FILE "
                          "(docs/verify.md)")
    return Archive(Path(fmu), entries)


def _xml(archive: Archive, path: str, data: bytes) -> ET.Element:
    try:
        return ET.fromstring(data)
    except ET.ParseError as e:
        raise VerifyError(archive.label(path), "", f"is not XML ({e})", REPACKAGE) from None


def _number(archive: Archive, path: str, where: str, text: str | None) -> float | None:
    if text is None:
        return None
    try:
        return float(text)
    except ValueError:
        raise VerifyError(archive.label(path), where, f"'{text}' is not a number",
                          REPACKAGE) from None


@dataclass
class Related:
    path: str
    role: str


def read_manifest(archive: Archive) -> list[Related]:
    """The manifest's related files (their archive paths and roles); the checksums go
    into the archive."""
    root = _xml(archive, MANIFEST, archive.entries[MANIFEST])
    related = []
    for i, node in enumerate(_children(root, "Related"), start=1):
        where = f"<Related> {i}"
        source, role = node.get("source"), node.get("role")
        if not source or not role:
            raise VerifyError(archive.label(MANIFEST), where, "has no source or role",
                              REPACKAGE)
        path = archive.resolve(MANIFEST, source, where)
        for checksum in _annotations(node, CHECKSUM):
            algorithm, value = checksum.get("algorithm", ""), checksum.get("value", "")
            if algorithm not in ALGORITHMS:
                raise VerifyError(archive.label(MANIFEST), f"{where} checksum",
                                  f"algorithm '{algorithm}' is unknown",
                                  f"use {' or '.join(ALGORITHMS)}")
            archive.checksums[path] = (algorithm, value)
        related.append(Related(path, role))
    for r in related:  # every listed file present and intact, before anything runs
        archive.read(r.path, "the manifest")
    return related


def _table(archive: Archive, path: str, listed_by: str) -> Table:
    data = archive.read(path, listed_by)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise VerifyError(archive.label(path), "", f"is not a CSV text file ({e})",
                          REPACKAGE) from None
    return read_table(Path(archive.label(path)), text)


def _parameters(archive: Archive, path: str, listed_by: str) -> dict[str, object]:
    """The values of an SSP parameter set (SSV) by name."""
    root = _xml(archive, path, archive.read(path, listed_by))
    values: dict[str, object] = {}
    for p in root.iter():
        if _local(p.tag) != "Parameter":
            continue
        name = p.get("name", "")
        for typed in p:
            kind, text = _local(typed.tag), typed.get("value")
            if text is None:
                continue
            if kind == "Real":
                values[name] = _number(archive, path, f"Parameter {name}", text)
            elif kind == "Integer":
                values[name] = int(_number(archive, path, f"Parameter {name}", text) or 0)
            elif kind == "Boolean":
                values[name] = text.strip().lower() in ("true", "1")
            else:
                values[name] = text
    return values


def _rules(archive: Archive, path: str, node: ET.Element):
    """The experiment's tolerances ({interface or None: {signal: rule}}) and event
    times from its annotation org.robofmu.verify."""
    rules: dict[str | None, dict[str, tolerance.Rule]] = {}
    events = []
    for e in _annotations(node, VERIFY):
        where = f"<Experiment name=\"{node.get('name')}\"> {_local(e.tag)}"
        if _local(e.tag) == "Event":
            events.append(_number(archive, path, where, e.get("time")))
        elif _local(e.tag) == "Tolerance":
            spec: object = ("cross-check" if e.get("rule") == "cross-check" else
                            {"abs": _number(archive, path, where, e.get("abs")) or 0.0,
                             "rel": _number(archive, path, where, e.get("rel")) or 0.0})
            try:
                rule = tolerance.from_json(spec)
            except ValueError as error:
                raise VerifyError(archive.label(path), where, str(error), REPACKAGE) from None
            rules.setdefault(e.get("interface"), {})[e.get("signal", "")] = rule
    return rules, [t for t in events if t is not None]


@dataclass
class Own:
    """One experiment the FMU carries: its case and its role."""

    case: Case
    role: str
    reference: str  # the reference's archive path
    source: str  # the file that defines it, as messages name it


def _experiment(archive: Archive, path: str, role: str, node: ET.Element, default,
                options) -> Own:
    name = node.get("name") or "experiment"
    where = f"<Experiment name=\"{name}\">"
    for analysis in ANALYSES:
        if _children(node, analysis):
            raise VerifyError(archive.label(path), where, f"is a {analysis} experiment",
                              "cosim verify runs TransientSimulation experiments only")
    settings = (_children(node, "TransientSimulation") or [node])[0]  # or the older draft's

    def setting(key: str, fallback):
        value = _number(archive, path, f"{where} {key}", settings.get(key))
        return fallback if value is None else value

    refs = _children(node, "References")
    if not refs:
        raise VerifyError(archive.label(path), where, "has no <References>",
                          "cosim verify compares with a reference: give the experiment one")
    reference_path = archive.resolve(path, refs[0].get("source", ""), where)
    reference = _table(archive, reference_path, path)
    stimuli = _children(node, "Stimuli")
    inputs = (_table(archive, archive.resolve(path, stimuli[0].get("source", ""), where), path)
              if stimuli else None)
    start_values: dict[str, object] = {}
    for p in _children(node, "Parameters"):
        start_values.update(_parameters(archive, archive.resolve(path, p.get("source", ""),
                                                                 where), path))
    rules, events = _rules(archive, path, node)
    fallback = _span(default, reference)
    start = setting("startTime", fallback[0])
    stop = setting("stopTime", fallback[1])
    step = setting("stepSize", fallback[2])
    rel_tol = _number(archive, path, f"{where} tolerance", node.get("tolerance"))
    case = Case(name=name, reference=reference, inputs=inputs, start=start, stop=stop,
                step=step, rel_tol=rel_tol if rel_tol is not None else default.rel_tol,
                start_values=casefile.start_values(archive.label(path), start_values),
                event_times=events, rules=rules,
                allow_early_end=bool(getattr(options, "allow_early_end", False)))
    return Own(case, role, reference_path, archive.label(path))


def _median_interval(reference: Table) -> float:
    steps = sorted(float(d) for d in (reference.time[1:] - reference.time[:-1]) if d > 0)
    return steps[len(steps) // 2] if steps else 0.0


@dataclass
class Default:
    """The FMU's DefaultExperiment; None where it says nothing."""

    start: float | None
    stop: float | None
    step: float | None
    rel_tol: float


def default_experiment(description) -> Default:
    e = description.defaultExperiment

    def value(name: str) -> float | None:
        v = getattr(e, name, None) if e is not None else None
        return None if v is None else float(v)

    tolerance = value("tolerance")
    return Default(value("startTime"), value("stopTime"), value("stepSize"),
                   DEFAULT_REL_TOL if tolerance is None else tolerance)


def _span(default: Default, reference: Table) -> tuple[float, float, float]:
    """Start, stop and step where an experiment gives none: the DefaultExperiment's,
    else the reference's first and last time and its median interval."""
    return (float(reference.time[0]) if default.start is None else default.start,
            float(reference.time[-1]) if default.stop is None else default.stop,
            default.step or _median_interval(reference))


def own_experiments(fmu: Path, description, options) -> list[Own]:
    """Every experiment the FMU carries, as cases with the command line's options
    applied; VerifyError when the archive is broken or names what cannot run."""
    archive = open_archive(fmu)
    related = read_manifest(archive)
    default = default_experiment(description)
    found: list[Own] = []
    named: set[str] = set()
    for r in related:
        if not r.role.startswith("experiment"):
            continue
        root = _xml(archive, r.path, archive.read(r.path, "the manifest"))
        for node in root.iter():
            if _local(node.tag) == "Experiment":
                own = _experiment(archive, r.path, r.role, node, default, options)
                named.add(own.reference)
                found.append(own)
    for r in related:  # a result no experiment names: the default experiment's
        if r.role == "result" and r.path not in named:
            reference = _table(archive, r.path, "the manifest")
            start, stop, step = _span(default, reference)
            case = Case(name=f"default experiment ({posixpath.basename(r.path)})",
                        reference=reference, inputs=None, start=start, stop=stop, step=step,
                        rel_tol=default.rel_tol,
                        allow_early_end=bool(getattr(options, "allow_early_end", False)))
            found.append(Own(case, "result", r.path, archive.label(MANIFEST)))
    if not found:
        raise VerifyError(archive.label(MANIFEST), "", "lists no experiment and no result",
                          "give a case folder or --reference FILE (docs/verify.md)")
    names = [o.case.name for o in found]
    for own in found:
        if names.count(own.case.name) > 1:
            raise VerifyError(archive.label(MANIFEST), own.case.name, "two experiments "
                              "have this name", "give each experiment its own name")
        if options.step is not None:
            own.case.step = options.step
        check_case(own.case, own.source, options, f"{own.case.name}: stepSize")
        apply_options(own.case, options)
    return found
