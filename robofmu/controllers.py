"""The controller of a hand-written closed-loop scenario: ``controller = "pid"`` (the
default, the thesis's PID with the plant's gravity compensation as feedforward) or
``controller = "computed-torque"`` (the ComputedTorque FMU: inverse dynamics of its own
model of the robot plus PID feedback, docs/computed-torque.md). Both drive the plant's
generalizedForceCommand, so the plant and the planner are the same in either loop.

A computed-torque scenario names its FMUs ``planner``, ``ct`` and ``plant``; its gains
come from the design rule ``[gains] omega = "30 rad/s"`` (triple pole at -omega of the
error dynamics e'' + Kd e' + Kp e + Ki int(e) = 0: Kd = 3 w, Kp = 3 w^2, Ki = w^3, the
Rust library's computed_torque::pole_placement; with ``integral = false`` a double pole
and no integral: Kd = 2 w, Kp = w^2); its model of the robot is the plant's (the
``[plant]`` table's values under the same names) unless ``[model]`` sets a parameter
apart (the model-mismatch study: ``[model] legMass = "1.13604 kg"``)."""

from __future__ import annotations

from dataclasses import dataclass

from .errors import ScenarioError

KINDS = ("pid", "computed-torque")


@dataclass(frozen=True)
class Loop:
    """The controller's side of a closed loop: its FMU alias, the connections
    (source alias, output, target alias, input) per axis, and a variable its FMU must
    have (a wrong FMU in its slot is named as such)."""

    alias: str
    connections: tuple
    role_variable: str


LOOPS = {
    "pid": Loop("pid", (("planner", "q", "pid", "setpoint"),
                        ("planner", "qdot", "pid", "setpointRate"),
                        ("plant", "theta", "pid", "measurement"),
                        ("plant", "thetaDot", "pid", "measuredRate"),
                        ("plant", "gravityCompensation", "pid", "feedforward"),
                        ("pid", "u", "plant", "generalizedForceCommand")), "Kp[1]"),
    "computed-torque": Loop("ct", (("planner", "q", "ct", "setpoint"),
                                   ("planner", "qdot", "ct", "setpointRate"),
                                   ("planner", "qddot", "ct", "setpointAcceleration"),
                                   ("plant", "theta", "ct", "measurement"),
                                   ("plant", "thetaDot", "ct", "measuredRate"),
                                   ("ct", "u", "plant", "generalizedForceCommand")),
                            "setpointAcceleration[1]"),
}


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
    kp, kd, ki = (3.0 * w * w, 3.0 * w, w ** 3) if integral else (w * w, 2.0 * w, 0.0)
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
