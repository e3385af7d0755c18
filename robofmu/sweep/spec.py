"""Sweep specifications: a base scenario plus what varies, expanded into runs.

A SPEC is a TOML file (every key, type, default and limit: docs/sweeps.md)::

    scenario = "../scenarios/three_axis_quintic.toml"   # relative to the SPEC file
    name = "gains"            # output names (optional, default: the SPEC file's stem)
    seed = 1                  # random samples (required with [random])
    samples = 20              # random draws (required with [random])

    [grid.'gains.omega']      # a grid: from/to/steps, or values = [...]
    from = 10
    to = 60
    steps = 11
    unit = "rad/s"            # written into the scenario as "<value> rad/s"

    [random.'plant.platformMass']
    distribution = "normal"   # normal (mean, sd), uniform (low, high); min/max truncate
    mean = 2.0
    sd = 0.2
    min = 1.5

    [workspace]               # end orientations on a grid, kept if reachable
    path = "motion.waypoints[1].angles"
    thx = {from = -10, to = 10, steps = 3}
    thy = {values = [0]}
    thz = {from = 130, to = 150, steps = 3}
    unit = "deg"

Every varied name is a path into the scenario document ("table.key", "list[index]",
indices from 0, none negative).
The runs are the product of the grid values, the reachable workspace targets and the
random draws (common random numbers: draw j is the same at every grid point). A
malformed SPEC raises SpecError naming the field.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import re
import tomllib
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import CosimError
from ..notes import say
from ..scenario import ScenarioError, fmu_file, parse_document

DISTRIBUTIONS = {"normal": ("mean", "sd"), "uniform": ("low", "high")}
MAX_RUNS = 1_000_000  # runs of one sweep (grid points x workspace targets x draws)
MAX_SEED = 2 ** 63 - 1
MAX_TARGETS = 10_000  # workspace targets, each checked by initialising the plant
KNOWN = {"scenario", "name", "seed", "samples", "grid", "random", "workspace", "fmu_dir"}
GRID_KEYS = {"from", "to", "steps", "values", "unit"}
RANDOM_KEYS = {"distribution", "mean", "sd", "low", "high", "min", "max", "unit"}
WORKSPACE_KEYS = {"path", "unit", "thx", "thy", "thz"}


class SpecError(ValueError):
    """A SPEC that cannot be run; the message names the field."""


@dataclass(frozen=True)
class Varied:
    """One varied quantity: its path in the scenario and the unit it is written with."""

    path: str
    unit: str | None
    kind: str  # "grid", "random" or "workspace"


@dataclass
class Spec:
    name: str
    scenario: Path
    document: dict
    varied: list[Varied]
    runs: list[dict] = field(default_factory=list)  # column -> value (float or list)
    fmu_dir: Path | None = None
    randoms: dict = field(default_factory=dict)  # path -> its [random] table

    def about(self) -> str:
        """A title: the sweep's name, its runs and what is drawn at random, how."""
        text = f"sweep {self.name}: {len(self.runs)} runs"
        for path, t in self.randoms.items():
            u = f" {t['unit']}" if "unit" in t else ""
            law = (f"normal, mean {t['mean']:g}{u}, sd {t['sd']:g}{u}"
                   if t.get("distribution") == "normal"
                   else f"uniform in [{t.get('low'):g}, {t.get('high'):g}]{u}")
            if "min" in t or "max" in t:
                law += (f", truncated to [{t.get('min', -math.inf):g}, "
                        f"{t.get('max', math.inf):g}]{u}")
            text += f"; random {path}: {law}"
        if self.randoms:
            draws = len({run_id({k: v for k, v in r.items()
                                 if k not in self.randoms}) for r in self.runs})
            text += f" ({len(self.runs) // max(draws, 1)} draws per grid point, the same at each)"
        return text


def _unknown(table: dict, allowed: set, where: str) -> None:
    """Refuses a key of `table` outside `allowed`, naming it and the allowed ones."""
    unknown = sorted(set(table) - allowed)
    if unknown:
        prefix = f"{where}." if where else ""
        raise SpecError(f"unknown field '{prefix}{unknown[0]}'; allowed: "
                        f"{', '.join(sorted(allowed))} (docs/sweeps.md)")


def _number(table: dict, key: str, where: str) -> float:
    if key not in table:
        raise SpecError(f"missing field '{where}.{key}' (docs/sweeps.md)")
    value = table.get(key)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SpecError(f"field '{where}.{key}' must be a finite number, got {value!r}")
    return float(value)


def _unit(table: dict, where: str) -> str | None:
    unit = table.get("unit")
    if unit is not None and not isinstance(unit, str):
        raise SpecError(f"field '{where}.unit' must be a string, got {unit!r}")
    return unit


def grid_values(table, where: str) -> list[float]:
    """from/to/steps (inclusive, evenly spaced) or an explicit values list."""
    if not isinstance(table, dict):
        raise SpecError(f"field '{where}' must be a table (from/to/steps or values)")
    _unknown(table, GRID_KEYS if where.startswith("grid.") else {"from", "to", "steps",
                                                                 "values"}, where)
    if "values" in table and ({"from", "to", "steps"} & set(table)):
        raise SpecError(f"field '{where}': give from/to/steps or values, not both")
    if "values" in table:
        values = table["values"]
        if not isinstance(values, list) or not values:
            raise SpecError(f"field '{where}.values' must be a non-empty list")
        if len(values) > MAX_RUNS:
            raise SpecError(f"field '{where}.values' has {len(values)} values, above the "
                            f"{MAX_RUNS} runs a sweep may have; give fewer values")
        return [_number({"v": v}, "v", f"{where}.values") for v in values]
    start, stop = _number(table, "from", where), _number(table, "to", where)
    steps = table.get("steps")
    if isinstance(steps, bool) or not isinstance(steps, int) or steps < 1:
        raise SpecError(f"field '{where}.steps' must be a positive integer, got {steps!r}")
    if steps > MAX_RUNS:
        raise SpecError(f"field '{where}.steps' = {steps} is above the {MAX_RUNS} runs a "
                        "sweep may have; give fewer steps")
    if steps == 1:
        return [start]
    return [start + (stop - start) * k / (steps - 1) for k in range(steps)]


def _draw(rng: np.random.Generator, table: dict, where: str) -> float:
    kind = table.get("distribution")
    if kind not in DISTRIBUTIONS:
        raise SpecError(f"field '{where}.distribution' must be one of "
                        f"{sorted(DISTRIBUTIONS)}, got {kind!r}")
    other = {k for d, keys in DISTRIBUTIONS.items() if d != kind for k in keys}
    _unknown(table, RANDOM_KEYS - other, where)
    a, b = (_number(table, key, where) for key in DISTRIBUTIONS[kind])
    low = _number(table, "min", where) if "min" in table else -math.inf
    high = _number(table, "max", where) if "max" in table else math.inf
    if kind == "normal" and b <= 0.0:
        raise SpecError(f"field '{where}.sd' must be positive, got {b}")
    if kind == "uniform" and b <= a:
        raise SpecError(f"field '{where}.high' must be above '{where}.low'")
    if not low < high:
        raise SpecError(f"field '{where}.max' must be above '{where}.min'")
    for _ in range(100000):  # rejection sampling: the truncated distribution
        x = float(rng.normal(a, b) if kind == "normal" else rng.uniform(a, b))
        if low <= x <= high:
            return x
    raise SpecError(f"field '{where}': min/max leave (almost) no probability")


def random_draws(tables: dict, seed, samples) -> list[list[float]]:
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed <= MAX_SEED:
        raise SpecError(f"field 'seed' must be an integer from 0 to 2^63 - 1 with [random], "
                        f"got {seed!r}")
    if isinstance(samples, bool) or not isinstance(samples, int) or samples < 1:
        raise SpecError(f"field 'samples' must be a positive integer, got {samples!r}")
    if samples > MAX_RUNS:
        raise SpecError(f"field 'samples' = {samples} is above the {MAX_RUNS} runs a sweep "
                        "may have; give fewer samples")
    rng = np.random.Generator(np.random.PCG64(seed))
    return [[_draw(rng, table, f"random.{path}") for path, table in tables.items()]
            for _ in range(samples)]


_STEP = re.compile(r"([^.\[\]]+)|\[(\d+)\]")
PATH_FORM = ("a path like \"table.key\" or \"list[0].key\" (list indices count from 0, "
             "as in the scenario's own messages: motion.waypoints[0] is the first "
             "waypoint; no negative indices)")


def _keys(path: str) -> list:
    """The steps of a path ("table.key", "list[0]"), or SpecError naming it."""
    keys = [m.group(1) if m.group(1) is not None else int(m.group(2))
            for m in _STEP.finditer(path)] if isinstance(path, str) else []
    if not keys or "".join(f".{k}" if isinstance(k, str) else f"[{k}]" for k in keys
                           ).lstrip(".") != path:
        raise SpecError(f"field '{path}' is not {PATH_FORM}")
    return keys


def get_path(document: dict, path: str):
    """document[path], or SpecError naming path."""
    node = document
    for key in _keys(path):
        _check_step(node, key, path)
        if isinstance(key, str) and key not in node:
            raise SpecError(f"field '{path}': '{key}' does not exist in the scenario")
        node = node[key]
    return node


def set_path(document: dict, path: str, value) -> None:
    """Sets document[path] (tables created as needed), or raises SpecError naming path."""
    keys = _keys(path)
    node = document
    for key, following in zip(keys, keys[1:]):
        _check_step(node, key, path)
        if isinstance(key, str) and key not in node:
            node[key] = {} if isinstance(following, str) else []
        node = node[key]
    _check_step(node, keys[-1], path)
    node[keys[-1]] = value


def _check_step(node, key, path: str) -> None:
    """Refuses `node[key]` unless node is a table (key a name) or a list (key an index
    below its length), naming the path."""
    if isinstance(key, int):
        if not isinstance(node, list):
            raise SpecError(f"field '{path}': [{key}] indexes something that is not a list "
                            "in the scenario")
        if key >= len(node):
            raise SpecError(f"field '{path}': index [{key}] is past the end of a list of "
                            f"{len(node)} (indices 0 to {len(node) - 1})")
    elif not isinstance(node, dict):
        raise SpecError(f"field '{path}': '{key}' does not exist in the scenario")


def written(value, unit: str | None):
    """The value as the scenario states it: "<value> <unit>" or the bare number."""
    if unit is None:
        return value
    if isinstance(value, list):
        return ", ".join(repr(v) for v in value) + f" {unit}"
    return f"{value!r} {unit}"


def run_id(values: dict) -> str:
    """A stable identity of a run: its varied values (for --resume)."""
    text = json.dumps(values, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _tables(data: dict, key: str) -> dict:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise SpecError(f"field '{key}' must be a table of \"path\" = {{...}}")
    return value


def load_spec(path: str | Path, fmu_dir: str | Path | None = None,
              reachable=None) -> Spec:
    """Reads a SPEC; `reachable(pose)` filters workspace targets (default: all kept)."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text())
    except (OSError, ValueError) as e:  # TOMLDecodeError and UnicodeDecodeError
        raise SpecError(f"{path}: cannot read the SPEC: {e}") from e
    try:
        return parse_spec(data, path.parent, path.stem, fmu_dir, reachable)
    except SpecError as e:
        raise SpecError(f"{path}: {e}") from e


def parse_spec(data: dict, base: Path, default_name: str, fmu_dir=None,
               reachable=None) -> Spec:
    _unknown(data, KNOWN, "")
    if not isinstance(data.get("scenario"), str):
        raise SpecError("field 'scenario' must name the base scenario file")
    scenario = (base / data["scenario"]).resolve()
    try:
        document = tomllib.loads(scenario.read_text())
    except (OSError, ValueError) as e:  # TOMLDecodeError and UnicodeDecodeError
        raise SpecError(f"field 'scenario': cannot read {scenario}: {e}") from e
    name = data.get("name", default_name)
    if not isinstance(name, str) or not re.fullmatch(r"[\w.-]+", name):
        raise SpecError(f"field 'name' must be a file-name-safe string, got {name!r}")
    if fmu_dir is None and "fmu_dir" in data:
        fmu_dir = base / str(data["fmu_dir"])
    check_fmus(document, scenario, fmu_dir)
    grid, randoms = _tables(data, "grid"), _tables(data, "random")
    varied: list[Varied] = []
    axes: list[list] = []  # the values of each grid axis, then the workspace targets
    for p, table in grid.items():
        axes.append(grid_values(table, f"grid.{p}"))
        varied.append(Varied(p, _unit(table, f"grid.{p}"), "grid"))
    targets = workspace_targets(data.get("workspace"), reachable)
    if targets is not None:
        unit = _unit(data["workspace"], "workspace")
        varied.append(Varied(data["workspace"]["path"], unit, "workspace"))
        axes.append(targets)
    _check_size(axes, data.get("samples") if randoms else 1)
    draws: list[list] = [[]]
    if randoms:
        draws = random_draws(randoms, data.get("seed"), data.get("samples"))
        varied += [Varied(p, _unit(t, f"random.{p}"), "random") for p, t in randoms.items()]
    elif "samples" in data or "seed" in data:
        raise SpecError("field 'samples'/'seed' needs a [random] table")
    if not varied:
        raise SpecError("nothing varies: give a [grid], [random] or [workspace] table")
    probe = json.loads(json.dumps(document))
    _design_on_the_base_plant(probe, varied)
    if probe != document:
        drawn = ", ".join(v.path for v in varied if v.kind == "random"
                          and v.path.startswith("plant."))
        say(f"the PID gains (gains.omega) are designed for the base scenario's plant, not "
            f"for each draw of {drawn} (gains.design_plant is set to the base plant: the "
            "drawn robot is the uncertainty the design does not know); set "
            "gains.design_plant in the scenario to choose otherwise")
    runs = []
    for point in itertools.product(*axes):
        for draw in draws:
            runs.append({v.path: value for v, value in zip(varied, [*point, *draw])})
    spec = Spec(name, scenario, document, varied, runs,
                Path(fmu_dir).resolve() if fmu_dir is not None else None, dict(randoms))
    if runs:
        check_document(spec, runs[0])
    return spec


def _check_size(axes: list[list], samples) -> None:
    """Refuses a product of grid points, targets and draws above MAX_RUNS before it is
    expanded (an integer `samples` only: random_draws reports other values)."""
    total = math.prod(len(a) for a in axes)
    if isinstance(samples, int) and not isinstance(samples, bool) and samples > 0:
        if samples > MAX_RUNS:
            raise SpecError(f"field 'samples' = {samples} is above the {MAX_RUNS} runs a "
                            "sweep may have; give fewer samples")
        total *= samples
    if total > MAX_RUNS:
        raise SpecError(f"fields 'grid'/'workspace'/'samples': {total} runs, above the "
                        f"{MAX_RUNS} a sweep may have; vary fewer values")


def check_fmus(document: dict, scenario: Path, fmu_dir) -> None:
    """Each FMU of the base scenario is a file and an FMU (a zip archive holding
    modelDescription.xml), before anything loads it."""
    fmus = document.get("fmus", {})
    for alias, name in (fmus.items() if isinstance(fmus, dict) else []):
        path = fmu_file(alias, str(name), scenario.parent, fmu_dir)
        fix = "build the FMUs (scripts/build-fmus.sh) or give --fmu-dir"
        if not path.is_file():
            raise SpecError(f"field 'fmus.{alias}' of the scenario: {path} is not a file; "
                            f"{fix}")
        try:
            with zipfile.ZipFile(path) as archive:
                archive.getinfo("modelDescription.xml")
        except (zipfile.BadZipFile, KeyError, OSError):
            raise SpecError(f"field 'fmus.{alias}' of the scenario: {path} is not an FMU "
                            f"(a zip archive with modelDescription.xml); {fix}") from None


def workspace_targets(table, reachable) -> list[list[float]] | None:
    if table is None:
        return None
    if not isinstance(table, dict) or not isinstance(table.get("path"), str):
        raise SpecError("field 'workspace.path' must name the angles to vary")
    _unknown(table, WORKSPACE_KEYS, "workspace")
    axes = [grid_values(table.get(a), f"workspace.{a}") for a in ("thx", "thy", "thz")]
    if math.prod(len(a) for a in axes) > MAX_TARGETS:
        raise SpecError(f"field 'workspace': {math.prod(len(a) for a in axes)} targets, "
                        f"above {MAX_TARGETS} (each is checked on the plant FMU); give "
                        "fewer values")
    targets = [list(p) for p in itertools.product(*axes)]
    if reachable is not None:
        scale = math.pi / 180.0 if table.get("unit") == "deg" else 1.0
        targets = [p for p in targets if reachable([scale * x for x in p])]
    return targets


def _design_on_the_base_plant(document: dict, varied: list[Varied]) -> None:
    """A plant parameter drawn at random is the robot's uncertainty, which the PID's
    gain design cannot know: the design rule then keeps the base scenario's plant
    (gains.design_plant), as it would for the real robot. A grid over a plant parameter
    is a family of robots, each designed for."""
    gains = document.get("gains")
    if (isinstance(gains, dict) and "omega" in gains and "design_plant" not in gains
            and document.get("controller", "pid") == "pid"
            and any(v.kind == "random" and v.path.startswith("plant.") for v in varied)):
        gains["design_plant"] = dict(document.get("plant", {}))


def document_for(spec: Spec, values: dict) -> dict:
    """The scenario document of one run: the base with the varied values written in."""
    document = json.loads(json.dumps(spec.document))
    _design_on_the_base_plant(document, spec.varied)
    for v in spec.varied:
        set_path(document, v.path, written(values[v.path], v.unit))
    return document


def check_document(spec: Spec, values: dict) -> None:
    """Resolves one run's scenario on the client, so that a bad path or unit is refused
    before anything is sent to the cluster. Values the plant FMU refuses (the gain design
    cannot measure such a plant) are no SPEC error: that run fails with the FMU's reason."""
    try:
        parse_document(document_for(spec, values), spec.scenario.parent, spec.fmu_dir)
    except ScenarioError as e:
        raise SpecError(f"the varied scenario is invalid: {e}") from e
    except CosimError:
        pass
