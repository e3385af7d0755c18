"""The main demo: the six PID scenarios of SCENARIOS through the FMUs, with CSVs, plots and a
summary table, then the PID against the computed-torque controller on each
(robofmu.demo_controllers).  ``python -m robofmu.demo [--out results]``."""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

from . import bundle
from .cli import entry
from .demo_controllers import print_comparison
from .errors import output_path
from .master import Master
from .outputs import write_outputs
from .report import (HEADER, format_table, metrics, sig, plot_cubic_vs_quintic, plot_tracking,
                     read_csv)
from .scenario import load_scenario

ROOT = Path(__file__).resolve().parent.parent
SCENARIOS = ["regulation", "path1_cubic", "path1_quintic", "three_axis_cubic",
             "three_axis_quintic", "three_axis_waypoints"]


def boundary_mismatch(cubic: dict, quintic_file: Path) -> float:
    """Largest |planned acceleration - boundary acceleration| of the cubic at t0 and tf
    (rad/s^2); the quintic meets the boundary accelerations by construction."""
    scenario = load_scenario(quintic_file)
    p = scenario.parameters["planner"]
    worst = 0.0
    for i in (1, 2, 3):
        a = cubic[f"planner.qddot[{i}]"]
        worst = max(worst, abs(a[0] - p[f"qddot0[{i}]"]), abs(a[-1] - p[f"qddotf[{i}]"]))
    return worst


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--out", type=output_path, default=Path("results"),
                        help="directory for the CSVs and plots (default: results/ here)")


def main(argv=None) -> int:
    """``python -m robofmu.demo ...``: ``cosim demo ...`` (its errors, exit codes)."""
    return entry("demo", argv)


def run(args: argparse.Namespace) -> int:
    args.out.mkdir(parents=True, exist_ok=True)
    results, rows, walls = {}, [], {}
    for name in SCENARIOS:
        path = bundle.scenarios_dir() / f"{name}.toml"
        scenario = load_scenario(path)  # errors: one line and exit code by robofmu.cli
        started = time.perf_counter()
        result = Master(scenario).run()
        walls[name] = time.perf_counter() - started
        csv_path = args.out / f"{name}.csv"
        write_outputs(scenario, result, args.out, plots=False)  # CSV, units, summary
        results[name] = read_csv(csv_path)
        reference_path = ROOT / "tests" / "closed_loop_references" / name / f"{name}_ref.csv"
        reference = read_csv(reference_path) if reference_path.exists() else None
        plot_tracking(results[name], name, args.out, reference)
        rows.append([name, *metrics(results[name]).row(), f"{walls[name]:.2f}"])
    print(format_table(["scenario", *HEADER, "wall (s)"], rows))
    print()
    print_comparison([bundle.scenarios_dir() / f"{n}.toml" for n in SCENARIOS], results)
    print()
    comparison = []
    for motion in ("path1", "three_axis"):
        cubic, quintic = results[f"{motion}_cubic"], results[f"{motion}_quintic"]
        plot_cubic_vs_quintic(cubic, quintic, motion, args.out)
        mismatch = boundary_mismatch(cubic, bundle.scenarios_dir() / f"{motion}_quintic.toml")
        mc, mq = metrics(cubic), metrics(quintic)
        comparison.append([motion, sig(math.degrees(mismatch)),
                           f"{sig(mc.peak_force_n)} / {sig(mq.peak_force_n)}",
                           f"{sig(math.degrees(mc.peak_angular_acceleration))} / "
                           f"{sig(math.degrees(mq.peak_angular_acceleration))}",
                           f"{sig(mc.rms_error_deg)} / {sig(mq.rms_error_deg)}"])
    print(format_table(["motion", "cubic accel jump at ends (deg/s^2)",
                        "peak |f| cubic / quintic (N)",
                        "peak |omega_dot| cubic / quintic (deg/s^2)",
                        "RMS error cubic / quintic (deg)"], comparison))
    steps = load_scenario(bundle.scenarios_dir() / "three_axis_quintic.toml").steps
    print(f"\nwall time of the 2 s loop at 1 kHz ({steps} steps, three FMUs, FMPy): "
          f"{walls['three_axis_quintic']:.2f} s; results in {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
