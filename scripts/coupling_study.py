"""Coupling error against step size, held inputs vs linear input extrapolation:
``python scripts/coupling_study.py [scenario ...]`` (a study, not part of the package).

For each scenario (names under scenarios/) and each step h = 4, 2, 1 ms, the master
runs with input_extrapolation = "hold" and "linear"; the error is the largest
|theta - theta_ref| (deg, any axis, at every 4 ms) against a reference run of the same
master at h = 1/16 ms with linear extrapolation (its own distance to the hold
reference at 1/16 ms is printed: the reference's accuracy). The step each needs for
0.05 deg follows from the error's order, fitted on the two smallest steps, and the
cost per step is the master's median loop time per step (interleaved runs); the last
column is the run time at that step relative to hold.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import tomllib
from pathlib import Path

import numpy as np

from cosim.master import Master
from cosim.scenario import parse_document

ROOT = Path(__file__).resolve().parent.parent
STEPS = (4e-3, 2e-3, 1e-3)
REFERENCE_STEP = 1e-3 / 16
SAMPLE = 4e-3
TARGET_DEG = 0.05


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


def step_for(errors: dict[float, float]) -> float:
    """The step giving TARGET_DEG from error = C h^p fitted on the two smallest steps."""
    (h1, e1), (h2, e2) = sorted(errors.items())[:2]
    p = math.log(e2 / e1) / math.log(h2 / h1)
    return h1 * (TARGET_DEG / e1) ** (1.0 / p)


def study(name: str, repeats: int) -> None:
    ref, _ = theta_at_samples(name, REFERENCE_STEP, "linear")
    ref_hold, _ = theta_at_samples(name, REFERENCE_STEP, "hold")
    print(f"{name}: reference h = {1e3 * REFERENCE_STEP:.4f} ms (linear); hold at that "
          f"step differs by {math.degrees(np.abs(ref_hold - ref).max()):.2e} deg")
    errors = {"hold": {}, "linear": {}}
    costs = {"hold": [], "linear": []}
    for h in STEPS:
        for mode in errors:
            theta, _ = theta_at_samples(name, h, mode)
            errors[mode][h] = math.degrees(float(np.abs(theta - ref).max()))
    for _ in range(repeats):  # interleaved: the machine's load hits both alike
        for mode in costs:
            costs[mode].append(theta_at_samples(name, 1e-3, mode)[1])
    cost = {mode: statistics.median(c) for mode, c in costs.items()}
    print(f"  {'h (ms)':>8} {'hold (deg)':>12} {'linear (deg)':>13} {'ratio':>7}")
    for h in STEPS:
        e0, e1 = errors["hold"][h], errors["linear"][h]
        print(f"  {1e3 * h:8.1f} {e0:12.3e} {e1:13.3e} {e0 / e1:7.1f}")
    need = {mode: step_for(errors[mode]) for mode in errors}
    if max(errors["hold"].values()) < TARGET_DEG and max(errors["linear"].values()) < TARGET_DEG:
        print(f"  both meet {TARGET_DEG} deg at every step up to {1e3 * max(STEPS):.0f} ms; "
              f"per step: hold {1e6 * cost['hold']:.1f} us, linear {1e6 * cost['linear']:.1f} us")
        return
    for mode in errors:
        time = cost[mode] / need[mode] / (cost["hold"] / need["hold"])
        print(f"  {mode:>6}: {1e6 * cost[mode]:.1f} us per step; {TARGET_DEG} deg needs "
              f"h = {1e3 * need[mode]:.2f} ms; run time relative to hold {time:.2f}")


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
