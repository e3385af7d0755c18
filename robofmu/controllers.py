"""The controller of a hand-written closed-loop scenario: ``controller = "pid"`` (the
default, the thesis's PID with the plant's gravity compensation as feedforward) or
``controller = "computed-torque"`` (the ComputedTorque FMU: inverse dynamics of its own
model of the robot plus PID feedback, docs/computed-torque.md). Both drive the plant's
generalizedForceCommand, so the plant and the planner are the same in either loop.

A computed-torque scenario names its FMUs ``planner``, ``ct`` and ``plant``; its gains
come from the design rule ``[gains] omega = "30 rad/s"`` (triple pole at -omega of the
error dynamics e'' + Kd e' + Kp e + Ki int(e) = 0: Kd = 3 w, Kp = 3 w^2, Ki = w^3, as
the Rust library's computed_torque::pole_placement; with ``integral = false`` a double
pole and no integral: Kd = 2 w, Kp = w^2); its model of the robot is the plant's (the
``[plant]`` table's values under the same names) unless ``[model]`` sets a parameter
apart (the model-mismatch study: ``[model] legMass = "1.13604 kg"``).

The controllers' FMUs and connections and the gain rules are data, closed_loop.toml
beside this module, which the Rust reference reads too (src/closed_loop/form.rs)."""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from .errors import ScenarioError

#: The loop's one description, shared with the Rust reference (src/closed_loop/form.rs):
#: the controllers' FMUs and connections, and the gain rules.
FORM = tomllib.loads((Path(__file__).parent / "closed_loop.toml").read_text())
KINDS = tuple(FORM["controllers"])


@dataclass(frozen=True)
class Loop:
    """The controller's side of a closed loop: its FMU alias, the connections
    (source alias, output, target alias, input) per axis, and a variable its FMU must
    have (a wrong FMU in its slot is named as such)."""

    alias: str
    connections: tuple
    role_variable: str


def _loop(entry: dict) -> Loop:
    alias = {"planner": "planner", "plant": "plant", "controller": entry["alias"]}
    return Loop(entry["alias"], tuple((alias[a], x, alias[b], y)
                                      for a, x, b, y in entry["connections"]),
                entry["role_variable"])


LOOPS = {kind: _loop(entry) for kind, entry in FORM["controllers"].items()}


def rule_gains(rule: str, inertia: float, bandwidth: float) -> tuple[float, float, float]:
    """(Kp, Ki, Kd) of the gain rule `rule` of closed_loop.toml for an axis of inertia
    m = `inertia` and bandwidth w = `bandwidth`: factor * m * w * ... * w, in that order."""
    gains = []
    for name in ("Kp", "Ki", "Kd"):
        term = FORM["rules"][rule][name]
        gain = term["factor"] * inertia
        for _ in range(term["power"]):
            gain *= bandwidth
        gains.append(gain)
    return gains[0], gains[1], gains[2]


def kind_of(data: dict) -> str:
    """The scenario's ``controller`` (default "pid")."""
    kind = data.get("controller", "pid")
    if kind not in KINDS:
        raise ScenarioError(f"field 'controller' must be \"pid\" or \"computed-torque\", got "
                            f"{kind!r}")
    return kind


def pole_placement(raw: dict, quantity) -> dict:
    """The computed-torque gains Kp[i], Kd[i], Ki[i] of the design rule in `raw` (the
    scenario's [gains] table); `quantity` reads "value unit" text."""
    unknown = sorted(set(raw) - {"omega", "integral"})
    if unknown or "omega" not in raw:
        field = f"gains.{unknown[0]}" if unknown else "gains"
        raise ScenarioError(f"field '{field}': a computed-torque controller takes its gains "
                            "from the design rule: write 'gains.omega' (bandwidth, e.g. "
                            "\"30 rad/s\") and optionally 'gains.integral' (true or false)")
    w = quantity(raw["omega"], "angular velocity", "gains.omega")
    if not w > 0.0:
        raise ScenarioError(f"field 'gains.omega' must be positive, got {w}")
    integral = raw.get("integral", True)
    if not isinstance(integral, bool):
        raise ScenarioError(f"field 'gains.integral' must be true or false, got {integral!r}")
    kp, ki, kd = rule_gains("computed-torque" if integral else
                            "computed-torque-without-integral", 1.0, w)
    gains: dict[str, float] = {}
    for i in (1, 2, 3):
        gains |= {f"Kp[{i}]": kp, f"Kd[{i}]": kd, f"Ki[{i}]": ki}
    return gains


def model_names(md) -> list[str]:
    """The ComputedTorque FMU's model parameters (fixed: gains and limits are tunable)."""
    return [v.name for v in md.modelVariables
            if v.causality == "parameter" and v.variability == "fixed"]


def model_parameters(md, plant_values: dict, model_raw: dict, value_of) -> dict:
    """The controller's model: the plant's values of `plant_values` under the model's
    names, then the `[model]` table (`model_raw`) read by `value_of(value, name)`."""
    names = model_names(md)
    model = {k: v for k, v in plant_values.items() if k in names}
    for name, value in model_raw.items():
        if name not in names:
            raise ScenarioError(f"field 'model.{name}': not a model parameter of "
                                f"{md.modelName}; the model parameters are the plant's "
                                f"{', '.join(names[:8])}, ... (docs/fmus.md)")
        model[name] = value_of(value, name)
    return model
