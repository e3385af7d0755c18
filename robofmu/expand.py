"""The expanded (plain) form of a scenario as TOML: every FMU parameter in SI, the
connections, and the plan switches of a multi-segment motion. It is what the harness
runs after resolving a hand-written scenario, and what the Rust reference
(`robofmu closed-loop reference`, tests/closed_loop.rs) reads: the scenario rules
(units, Euler-rate conversion, gain design, workspace) are implemented once, here in
Python. ``cosim check SCENARIO --expanded FILE.toml`` writes it."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

from .limits import LIMITS
from .scenario import Scenario, ScenarioError

HEADER = "# Expanded by `cosim check {source} --expanded`: SI units, do not edit by hand.\n"


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("nan" if math.isnan(v) else
                                                   ("inf" if v > 0 else "-inf"))
    if isinstance(v, str):
        return json.dumps(v)  # a TOML basic string
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(f"no TOML form for {v!r}")


def _table(values: dict) -> list[str]:
    return [f"{json.dumps(k)} = {_value(v)}" for k, v in values.items()]


def expanded_toml(scenario: Scenario, out: Path, source: str) -> str:
    """The TOML text; FMU paths relative to the folder of `out`."""
    s = scenario
    folder = Path(out).resolve().parent
    lines = [HEADER.format(source=source).rstrip("\n")]
    described = {} if s.description is None else {"description": s.description}
    if s.controller != "pid":
        described["controller"] = s.controller
    lines += _table({"name": s.name, **described, "start_time": s.start_time,
                     "stop_time": s.stop_time, "step_size": s.step_size, "order": list(s.order),
                     "coupling": s.coupling, "max_step_halvings": s.max_step_halvings,
                     "record": [str(r) for r in s.record]})
    lines += ["", "[fmus]"] + _table({a: os.path.relpath(p, folder) for a, p in s.fmus.items()})
    if s.limits:
        unit = {"angle": "rad", "force": "N"}
        lines += ["", "[limits]"] + _table({k: f"{v!r} {unit[LIMITS[k][0]]}"
                                            for k, v in s.limits.items()})
    for field, table in (("sample_period", s.sample_period),
                         ("model_exchange", s.model_exchange)):
        if table:
            lines += ["", f"[{field}]"] + _table(table)
    for alias, values in s.parameters.items():
        lines += ["", f"[parameters.{alias}]"] + _table(values)
    for c in s.connections:
        lines += ["", "[[connections]]"] + _table({"from": str(c.source), "to": str(c.target)})
    for switch in s.schedule:
        lines += ["", "[[plan_switches]]"] + _table({"step": switch.step, "alias": switch.alias})
        lines += ["[plan_switches.parameters]"] + _table(switch.parameters)
    return "\n".join(lines) + "\n"


def same_file(a: Path, b: Path) -> bool:
    """Whether `a` names the file `b` (a link, another spelling of its path)."""
    try:
        return a.exists() and b.exists() and os.path.samefile(a, b)
    except OSError:
        return a.resolve() == b.resolve()


def check_target(target: Path, source: Path, option: str = "--expanded") -> None:
    """ScenarioError (naming `option`, the argument that gave `target`) unless `target`
    is a .toml file to write other than the scenario file `source`; checked before the
    scenario is read."""
    if target.suffix != ".toml" or target.is_dir():
        raise ScenarioError(f"{option}: {target}: name a .toml file to write")
    if same_file(target, source):
        raise ScenarioError(f"{option}: {target} is the scenario being checked; name "
                            f"another file (e.g. {option} results/expanded.toml)")


def write_expanded(scenario: Scenario, target: Path, source: Path) -> None:
    """Writes the expanded form of `scenario` (read from the file `source`) to `target`
    (checked by check_target), its folder made when missing."""
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(expanded_toml(scenario, target, source.name))
