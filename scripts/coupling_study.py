"""Coupling error against step size for each order of input extrapolation (held inputs,
linear, quadratic): ``python scripts/coupling_study.py [scenario ...]`` (a study, not part of
the package).

For each scenario (names under scenarios/) and each step h = 8, 4, 2, 1 ms, the master
runs with input_extrapolation = "hold", "linear" and "quadratic"; the error is the
largest |theta - theta_ref| (any axis, at every 8 ms) against a reference run of the
same master at h = 1/16 ms with quadratic extrapolation (its own distance to the linear
reference at 1/16 ms is printed: the reference's accuracy). The step each order needs
for 0.05 deg and for 1e-5 rad follows from error = C h^p fitted between the two
measured steps that bracket the target (or the two smallest), and the cost per step is
the master's median loop time per step (interleaved runs); the run time at the step
for 0.05 deg is given relative to hold ("<=": the order meets 0.05 deg at every
measured step, so its step is at least the largest one and its run time at most that).
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import tomllib
from pathlib import Path

import numpy as np

from robofmu.master import Master
from robofmu.scenario import parse_document

ROOT = Path(__file__).resolve().parent.parent
STEPS = (8e-3, 4e-3, 2e-3, 1e-3)
REFERENCE_STEP = 1e-3 / 16
SAMPLE = 8e-3
TARGET_DEG = 0.05
TARGET_RAD = 1e-5
MODES = ("hold", "linear", "quadratic")


def theta_at_samples(name: str, h: float, extrapolation: str) -> tuple[np.ndarray, float]:
    """theta (rad) every SAMPLE s and the loop's time per step."""
    path = ROOT / "scenarios" / f"{name}.toml"
    document = tomllib.loads(path.read_text())
    document["step_size"] = f"{h!r} s"
    document["input_extrapolation"] = extrapolation
    s = parse_document(document, path.parent)
    master = Master(s)
    result = master.run()
    every = round(SAMPLE / h)
    theta = np.column_stack([result.columns[f"plant.theta[{i}]"] for i in (1, 2, 3)])
    return theta[::every], master.loop_seconds / s.steps


def step_for(errors: dict[float, float], target: float) -> float:
    """The step giving `target` from error = C h^p between the two measured steps that
    bracket it (the two smallest when even the smallest misses it): no extrapolation
    beyond a step the error was measured at when a larger one misses, as a loop that
    turns unstable does."""
    points = sorted(errors.items())
    pair = points[:2]
    for low, high in zip(points, points[1:]):
        if low[1] <= target < high[1]:
            pair = [low, high]
            break
    (h1, e1), (h2, e2) = pair
    p = math.log(e2 / e1) / math.log(h2 / h1)
    return h1 * (target / e1) ** (1.0 / p)


def study(name: str, repeats: int) -> None:
    ref, _ = theta_at_samples(name, REFERENCE_STEP, "quadratic")
    ref_linear, _ = theta_at_samples(name, REFERENCE_STEP, "linear")
    print(f"{name}: reference h = {1e3 * REFERENCE_STEP:.4f} ms (quadratic); linear at that "
          f"step differs by {np.abs(ref_linear - ref).max():.2e} rad")
    errors: dict[str, dict[float, float]] = {mode: {} for mode in MODES}  # rad
    costs: dict[str, list[float]] = {mode: [] for mode in MODES}
    for h in STEPS:
        for mode in MODES:
            theta, _ = theta_at_samples(name, h, mode)
            errors[mode][h] = float(np.abs(theta - ref).max())
    for _ in range(repeats):  # interleaved: the machine's load hits every order alike
        for mode in MODES:
            costs[mode].append(theta_at_samples(name, 1e-3, mode)[1])
    cost = {mode: statistics.median(c) for mode, c in costs.items()}
    print(f"  {'h (ms)':>8}" + "".join(f" {m + ' (deg)':>17}" for m in MODES)
          + f" {'hold/quadratic':>15}")
    for h in STEPS:
        e = [math.degrees(errors[m][h]) for m in MODES]
        print(f"  {1e3 * h:8.1f}" + "".join(f" {x:17.3e}" for x in e)
              + f" {e[0] / e[-1]:15.1f}")
    target_rad = math.radians(TARGET_DEG)
    for mode in MODES:
        need = {label: (f"every step up to {1e3 * max(STEPS):.0f} ms"
                        if max(errors[mode].values()) < target
                        else f"h = {1e3 * step_for(errors[mode], target):.2f} ms")
                for label, target in ((f"{TARGET_DEG} deg", target_rad),
                                      (f"{TARGET_RAD:g} rad", TARGET_RAD))}
        print(f"  {mode:>9}: {1e6 * cost[mode]:5.1f} us per step; "
              + "; ".join(f"{label} needs {text}" for label, text in need.items()))
    step = {m: (max(STEPS) if max(errors[m].values()) < target_rad
                else step_for(errors[m], target_rad)) for m in MODES}
    bound = {m: "<=" if max(errors[m].values()) < target_rad else "" for m in MODES}
    if bound["hold"]:
        return  # hold meets it everywhere: no ratio to hold's run time
    relative = {m: cost[m] / step[m] / (cost["hold"] / step["hold"]) for m in MODES}
    print(f"  run time at {TARGET_DEG} deg relative to hold: "
          + ", ".join(f"{m} {bound[m]}{r:.2f}" for m, r in relative.items()))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python scripts/coupling_study.py",
                                     description=__doc__)
    parser.add_argument("scenarios", nargs="*", default=["regulation", "three_axis_quintic"])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args(argv)
    for name in args.scenarios:
        study(name, args.repeats)
    return 0


if __name__ == "__main__":
    sys.exit(main())
