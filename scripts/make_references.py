"""Writes the reference results under tests/references/<Model>/<case>/ from closed
forms evaluated with numpy, independently of the Rust code and without running any FMU:

* Planner: the boundary-condition system of the spec (4x4 cubic, 6x6 quintic) in
  absolute time, solved exactly (rational arithmetic), evaluated with numpy.polyval; at
  rest (q0 / qf, zero rates) outside [t0, tf].
* PID: the response to constant inputs from a zero state, by Laplace inversion:
  u(t) = Kp e + Ki e t + Kd e / Tf exp(-t/Tf) + ff (filtered error path) or
  Kd r (1 - exp(-t/Tf)) for the rate path, clamped to the limits (with conditional
  integration the integral stops exactly when the raw output reaches the limit, and
  the clamped output is the clamped straight line).
* ComputedTorque: a model reduced to the platform (massless legs and sliders) at rest
  in an upright pose, where the Euler-angle mass matrix is the platform's inertia
  tensor about P and gravity has no moment: u = I_B (Kp e + Ki e t) for held inputs.

Each case directory holds <Model>_ref.csv (cross-check format: quoted names, time
first), <Model>_ref.opt (StartTime, StopTime, StepSize, RelTol) and case.json (start
values, per-signal absolute tolerances for each interface, event times); a case driven
by inputs also holds <Model>_input.csv. The "defaults" cases have no start values: the
FMUs' default parameters and inputs (the FMI cross-check layout, scripts/cross-check.sh,
can express no other).

The files are the same bytes on every machine (tests/python/test_make_references.py
regenerates them and compares): the only operations whose last bit could depend on the
CPU are done exactly instead. The boundary-condition system is solved in rational
arithmetic (numpy.linalg.solve goes through OpenBLAS, whose kernels are chosen per
CPU, and its round-off differed in the last digits between machines), and exp is the
correctly rounded one of Python's decimal module (numpy's vectorised exp has CPU-specific
implementations: a 1-ulp difference between machines was seen). The rest is IEEE
arithmetic (+, -, *, / element by element), the same everywhere.

Run: .venv/bin/python scripts/make_references.py [--out DIRECTORY]
(default tests/references).
"""

import argparse
import json
from decimal import Context, Decimal
from fractions import Fraction
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent / "tests" / "references"
# 40 digits, then rounded once to double: the same double on every machine.
_EXP_CONTEXT = Context(prec=40)


def exp(x):
    """exp of every element of x, correctly rounded to 40 digits, then to double."""
    return np.array([float(Decimal(float(v)).exp(_EXP_CONTEXT)) for v in np.ravel(x)])


def write_signals(path, columns):
    """A CSV of quoted names, time first."""
    names = list(columns)
    data = np.column_stack([columns[n] for n in names])
    with open(path, "w") as f:
        f.write(",".join(f'"{n}"' for n in names) + "\n")
        for row in data:
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def write_case(model, case, options, columns, start_values, tolerances, event_times=(),
               inputs=None):
    directory = ROOT / model / case
    directory.mkdir(parents=True, exist_ok=True)
    write_signals(directory / f"{model}_ref.csv", columns)
    if inputs is not None:
        write_signals(directory / f"{model}_input.csv", inputs)
    with open(directory / f"{model}_ref.opt", "w") as f:
        for key in ["StartTime", "StopTime", "StepSize", "RelTol"]:
            f.write(f"{key}, {options[key]!r}\n")
    case_info = {
        "start_values": start_values,
        "tolerances": tolerances,
        "event_times": list(event_times),
    }
    with open(directory / "case.json", "w") as f:
        json.dump(case_info, f, indent=2, sort_keys=True)
        f.write("\n")


def grid(options):
    n = int(round((options["StopTime"] - options["StartTime"]) / options["StepSize"]))
    return options["StartTime"] + options["StepSize"] * np.arange(n + 1)


def polynomial(order, t0, tf, b):
    """Coefficients (highest power first) from the boundary-condition system."""
    def row(t, derivative, n):
        out = [Fraction(0)] * n
        for k in range(derivative, n):
            factor = int(np.prod(np.arange(k - derivative + 1, k + 1)))
            out[k] = factor * Fraction(t) ** (k - derivative)
        return out

    n = order + 1
    rows = [row(t0, 0, n), row(t0, 1, n), row(tf, 0, n), row(tf, 1, n)]
    rhs = [b["q0"], b["qdot0"], b["qf"], b["qdotf"]]
    if order == 5:
        rows += [row(t0, 2, n), row(tf, 2, n)]
        rhs += [b["qddot0"], b["qddotf"]]
    c = solve_exactly(rows, rhs)
    return np.array([float(x) for x in c[::-1]])


def solve_exactly(rows, rhs):
    """The solution of rows x = rhs in rational arithmetic (Gauss-Jordan elimination
    with a nonzero pivot; the inputs are doubles, hence exact fractions)."""
    a = [[Fraction(v) for v in r] + [Fraction(y)] for r, y in zip(rows, rhs)]
    n = len(a)
    for col in range(n):
        pivot = next(r for r in range(col, n) if a[r][col] != 0)
        a[col], a[pivot] = a[pivot], a[col]
        for r in range(n):
            if r != col and a[r][col] != 0:
                f = a[r][col] / a[col][col]
                a[r] = [x - f * y for x, y in zip(a[r], a[col])]
    return [a[r][n] / a[r][r] for r in range(n)]


def planner_case(case, order, t0, tf, boundaries, stop, at_defaults=False):
    """at_defaults: the arguments are the FMU's default parameters; no start values."""
    options = {"StartTime": 0.0, "StopTime": stop, "StepSize": 0.01, "RelTol": 1e-6}
    t = grid(options)
    columns = {"time": t}
    start_values = {} if at_defaults else {
        "order": order, "t0": t0, "tf": tf,
        **{f"{key}[{axis}]": value
           for axis, b in enumerate(boundaries, start=1) for key, value in b.items()}}
    for axis, b in enumerate(boundaries, start=1):
        p = polynomial(order, t0, tf, b)
        dp, ddp = np.polyder(p), np.polyder(p, 2)
        inside = (t >= t0) & (t <= tf)
        held = np.where(t < t0, b["q0"], np.polyval(p, tf))
        columns[f"q[{axis}]"] = np.where(inside, np.polyval(p, t), held)
        columns[f"qdot[{axis}]"] = np.where(inside, np.polyval(dp, t), 0.0)
        columns[f"qddot[{axis}]"] = np.where(inside, np.polyval(ddp, t), 0.0)
    # Pure evaluation of a polynomial in double precision: 1e-9 covers round-off of
    # the two formulations (shifted closed form vs. absolute-time solve).
    tol = {name: 1e-9 for name in columns if name != "time"}
    write_case("Planner", case, options, columns, start_values,
               {"CoSimulation": tol, "ModelExchange": tol}, event_times=(t0, tf))


def pid_channel(t, kp, ki, kd, tf, e, ff=0.0, rate_error=None, limits=None):
    if rate_error is None:
        d = kd * e / tf * exp(-t / tf) if kd != 0.0 else 0.0 * t
    else:
        d = kd * rate_error * (1.0 - exp(-t / tf))
    u = kp * e + ki * e * t + d + ff
    if limits is not None:
        u = np.clip(u, *limits)
    return u


def pid_cases():
    options = {"StartTime": 0.0, "StopTime": 2.0, "StepSize": 0.01, "RelTol": 1e-8}
    t = grid(options)
    start_values = {
        # channel 1: the defaults (Kp 1, Ki 0.5, Kd 0.1, Tf 0.05, setpoint 1)
        # channel 2: measurement, feedforward, other gains
        "Kp[2]": 2.0, "Ki[2]": 1.0, "Kd[2]": 0.05, "Tf[2]": 0.02,
        "setpoint[2]": 0.5, "measurement[2]": 0.2, "feedforward[2]": 0.3,
        # channel 3: derivative from the rate inputs
        "useRateInputs[3]": True, "Kp[3]": 0.5, "Ki[3]": 0.0, "Kd[3]": 0.4, "Tf[3]": 0.1,
        "setpoint[3]": -0.25, "setpointRate[3]": 0.0, "measuredRate[3]": -0.5,
    }
    columns = {
        "time": t,
        "u[1]": pid_channel(t, 1.0, 0.5, 0.1, 0.05, 1.0),
        "u[2]": pid_channel(t, 2.0, 1.0, 0.05, 0.02, 0.3, ff=0.3),
        "u[3]": pid_channel(t, 0.5, 0.0, 0.4, 0.1, -0.25, rate_error=0.5),
    }
    # Co-Simulation: exact discretisation of constant inputs, only round-off.
    # Model Exchange: FMPy's CVode at RelTol 1e-8; the fastest mode (Tf = 0.02 s,
    # amplitude 2.5) leaves errors of order 1e-7; 1e-5 bounds them with margin.
    names = ["u[1]", "u[2]", "u[3]"]
    tolerances = {"CoSimulation": {n: 1e-9 for n in names},
                  "ModelExchange": {n: 1e-5 for n in names}}
    write_case("PID", "step_responses", options, columns, start_values, tolerances)

    limited = {
        "Kp[1]": 1.0, "Ki[1]": 2.0, "Kd[1]": 0.0, "limitOutput[1]": True,
        "uMin[1]": -3.0, "uMax[1]": 3.0, "setpoint[1]": 1.0,
        "Kp[2]": 1.0, "Ki[2]": 2.0, "Kd[2]": 0.0, "limitOutput[2]": True,
        "uMin[2]": -2.0, "uMax[2]": 2.0, "setpoint[2]": -1.0,
        "setpoint[3]": 0.0,
    }
    columns = {
        "time": t,
        "u[1]": pid_channel(t, 1.0, 2.0, 0.0, 1.0, 1.0, limits=(-3.0, 3.0)),
        "u[2]": pid_channel(t, 1.0, 2.0, 0.0, 1.0, -1.0, limits=(-2.0, 2.0)),
        "u[3]": 0.0 * t,
    }
    tolerances = {"CoSimulation": {n: 1e-9 for n in names},
                  "ModelExchange": {n: 1e-5 for n in names}}
    write_case("PID", "saturation", options, columns, limited, tolerances)

    # The defaults: gains Kp 1, Ki 0.5, Kd 0.1, Tf 0.05 on every channel, error from the
    # default inputs (setpoint 1, 0.5, -0.25; everything else 0), held constant.
    columns = {"time": t, **{f"u[{i}]": pid_channel(t, 1.0, 0.5, 0.1, 0.05, e)
                             for i, e in enumerate([1.0, 0.5, -0.25], start=1)}}
    ends = np.array([options["StartTime"], options["StopTime"]])
    inputs = {"time": ends}
    for i, setpoint in enumerate([1.0, 0.5, -0.25], start=1):
        inputs[f"setpoint[{i}]"] = np.full(2, setpoint)
        for name in ("measurement", "setpointRate", "measuredRate", "feedforward"):
            inputs[f"{name}[{i}]"] = np.zeros(2)
    tolerances = {"CoSimulation": {n: 1e-9 for n in names},
                  "ModelExchange": {n: 1e-5 for n in names}}
    write_case("PID", "defaults", options, columns, {}, tolerances, inputs=inputs)


def computed_torque_case():
    """ComputedTorque with a model whose legs and sliders are massless, at rest in the
    start pose (0, 0, thz): the law's inverse dynamics is then the platform's alone,
    u = E^T R I_B R^T E a, and with thx = thy = 0 both E and R are Rz(thz), so
    M_x = I_B (the platform inertia about P in {B}) and u = I_B a; gravity acts through
    P and the centre of mass on the vertical, so G = 0. With the inputs held (zero
    rates and planned acceleration, error e), the integral is e t and
    a = Kp e + Ki e t: u is a straight line per axis, clamped at a limit (axis 3)."""
    options = {"StartTime": 0.0, "StopTime": 1.0, "StepSize": 0.01, "RelTol": 1e-8}
    t = grid(options)
    thz = np.radians(122.07)  # the start pose of docs/3pss-model.md, the FMU's default
    inertia = [0.011824, 0.011824, 0.022886]  # platformInertia[k,k] default, kg m^2
    kp, ki = 2700.0, 27000.0  # the default gains: triple pole at -30 rad/s (Kd unused)
    errors = [0.01, -0.02, 0.015]
    u_max = 5.0
    start_values = {"legMass": 0.0, "sliderMass": 0.0, "legTransverseInertia": 0.0,
                    "limitOutput[3]": True, "uMin[3]": -u_max, "uMax[3]": u_max}
    columns = {"time": t}
    for k, e in enumerate(errors):
        start_values[f"setpoint[{k + 1}]"] = [0.0, 0.0, thz][k] + e
        u = inertia[k] * (kp * e + ki * e * t)
        columns[f"u[{k + 1}]"] = np.minimum(u, u_max) if k == 2 else u
    # Co-Simulation: the held-input integral is exact; Model Exchange: the integral's
    # rate is constant, which CVode integrates exactly. Both leave only round-off
    # (measured 4e-14 N m on u up to 5 N m); 1e-9 N m as for the PID's exact cases.
    names = list(columns)[1:]
    tolerances = {"CoSimulation": {n: 1e-9 for n in names},
                  "ModelExchange": {n: 1e-9 for n in names}}
    write_case("ComputedTorque", "platform_only", options, columns, start_values, tolerances)


def main():
    global ROOT
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT,
                        help="directory of the <Model>/<case>/ folders (default: %(default)s)")
    ROOT = parser.parse_args().out
    planner_case("quintic_t0_0.5", 5, 0.5, 2.0, [
        {"q0": 0.1, "qf": 0.9, "qdot0": 0.2, "qdotf": -0.1, "qddot0": 0.5, "qddotf": -0.3},
        {"q0": -0.4, "qf": 0.0, "qdot0": 0.0, "qdotf": 0.0, "qddot0": 0.0, "qddotf": 0.0},
        {"q0": 2.13, "qf": 2.69, "qdot0": 0.322, "qdotf": 0.214, "qddot0": -0.0138, "qddotf": -0.088},
    ], stop=2.5)
    planner_case("cubic_with_rates", 3, 0.25, 1.75, [
        {"q0": 0.0, "qf": 1.0, "qdot0": 0.5, "qdotf": 0.0, "qddot0": 0.0, "qddotf": 0.0},
        {"q0": 1.0, "qf": -1.0, "qdot0": 0.0, "qdotf": -0.5, "qddot0": 0.0, "qddotf": 0.0},
        {"q0": 0.3, "qf": 0.3, "qdot0": 1.0, "qdotf": 1.0, "qddot0": 0.0, "qddotf": 0.0},
    ], stop=2.0)
    # The FMU's defaults: quintic rest to rest from 0 to (0.5, -0.3, 0.8) rad in [0, 2] s.
    planner_case("defaults", 5, 0.0, 2.0, [
        {"q0": 0.0, "qf": qf, "qdot0": 0.0, "qdotf": 0.0, "qddot0": 0.0, "qddotf": 0.0}
        for qf in (0.5, -0.3, 0.8)
    ], stop=2.5, at_defaults=True)
    pid_cases()
    computed_torque_case()


if __name__ == "__main__":
    main()
