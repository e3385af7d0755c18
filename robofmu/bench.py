"""Cost of the master per communication step against a minimal FMPy loop over the same
FMUs: ``python -m robofmu.bench [--runs 5] [scenario ...]`` (names under scenarios/, or
paths to .toml files).

Per scenario and run, in one process:
- minimal loop: FMPy's own calls alone, per step one getReal and one setReal per
  connected FMU pair and one doStep per FMU, nothing recorded;
- master: robofmu.master.Master (its native stepping loop, robofmu.loop), every
  connection and recorded signal stored each step, inputs held as the minimal loop
  holds them; then with linear and with quadratic input extrapolation.
Times are the stepping loops only (instantiation and initialisation excluded), medians
over the runs. Then the sweep throughput (``--sweep-runs``, 0 to skip): the same
closed-loop runs (the regulation scenario over a grid of bandwidths) serially in this
process and on LocalClusters of 1 and 2 workers, in runs per second between the first
and the last completed run. The last line is ``master/minimal ratio: X``, X the
master's median time per step over the minimal loop's, of the first scenario.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

from . import bundle
from .bench_container import print_container_lines
from .bench_sweep import add_sweep_options, run as bench_sweep
from .cli import entry
from .master import Master
from .scenario import load_scenario
from .sweep import run_sweep
from .sweep.spec import parse_spec

ROOT = Path(__file__).resolve().parent.parent


class _Timed(Master):
    """A master whose stepping loop is replaced by `loop(master)` (timed)."""

    def __init__(self, scenario, loop):
        super().__init__(scenario)
        self.stepping = loop

    def run(self):
        s = self.scenario
        self.fmus = {a: self.open_fmu(a, s.fmus[a], s) for a in s.order}
        try:
            for alias, values in s.parameters.items():
                self._initialize(alias, values)
            for alias in s.order:
                self.fmus[alias].enter_initialization()
            for alias in s.order:
                for source, variables, inputs in self.inputs[alias]:
                    self.fmus[alias].set_values(inputs,
                                                self.fmus[source].get_values(variables))
            for alias in s.order:
                self.fmus[alias].exit_initialization()
            started = time.perf_counter()
            self.stepping(self)
            self.loop_seconds = time.perf_counter() - started
        finally:
            for fmu in self.fmus.values():
                fmu.close()


def minimal_loop(master: Master) -> None:
    """FMPy calls alone: per pair getReal + setReal, then doStep per FMU (sampled)."""
    s = master.scenario
    refs = {a: {v.name: v.valueReference for v in f.variables.values()}
            for a, f in master.fmus.items()}
    pairs = [(master.fmus[src]._fmu, [refs[src][v] for v in variables],
              master.fmus[alias]._fmu, [refs[alias][v] for v in inputs])
             for alias in s.order for src, variables, inputs in master.inputs[alias]]
    slaves = [master.fmus[a]._fmu for a in s.order]
    h = s.step_size
    for k in range(s.steps):
        for source, src_refs, target, dst_refs in pairs:
            target.setReal(dst_refs, source.getReal(src_refs))
        t = s.start_time + k * h
        for slave in slaves:
            slave.doStep(t, h)


def _median_per_step(scenario, make, runs: int) -> float:
    per_step = []
    for _ in range(runs):
        m = make(scenario)
        m.run()
        per_step.append(m.loop_seconds / scenario.steps)
    return statistics.median(per_step)


def sweep_throughput(runs: int) -> None:

    omegas = [10.0 + 40.0 * k / max(runs - 1, 1) for k in range(runs)]
    data = {"scenario": str(bundle.scenarios_dir() / "regulation.toml"), "name": "bench",
            "grid": {"gains.omega": {"values": omegas, "unit": "rad/s"}}}
    spec = parse_spec(data, ROOT, "bench")
    steps = load_scenario(spec.scenario).steps
    print(f"sweep throughput: {runs} runs of regulation ({steps} steps each), runs/s "
          "between the first and the last completed run:")
    with tempfile.TemporaryDirectory() as out:
        for label, workers in (("serial, in process", 0), ("LocalCluster, 1 worker", 1),
                               ("LocalCluster, 2 workers", 2)):
            outcome = run_sweep(spec, Path(out) / label.replace(" ", "_"), workers=workers,
                                progress=False, plots=False)
            print(f"  {label:28s} {outcome.throughput():6.2f} runs/s ({outcome.failed} "
                  f"failed, {outcome.wall_s:.1f} s with start-up)")


def _scenario_path(name: str) -> Path:
    """A scenario file path, or the name of one under scenarios/."""
    return Path(name) if name.endswith(".toml") else bundle.scenarios_dir() / f"{name}.toml"


def _count(low: int):
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            value = -1
        if not low <= value <= 1000:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number in {low}..1000")
        return value
    return parse


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scenarios", nargs="*", default=["three_axis_quintic"],
                        help="scenario names or files; or 'sweep': the sweep throughput per "
                        "worker count (cosim bench sweep --runs N --workers 0,1,2)")
    parser.add_argument("--runs", type=int, default=None,
                        help="runs per median (default 5); with 'sweep': runs per sweep "
                        "(default 200)")
    parser.add_argument("--sweep-runs", type=_count(0), default=24,
                        help="closed-loop runs per sweep throughput measurement (0: skip)")
    add_sweep_options(parser)


def main(argv=None) -> int:
    """``python -m robofmu.bench ...``: ``cosim bench ...`` (robofmu.cli)."""
    return entry("bench", argv)


def run(args: argparse.Namespace) -> int:
    if args.scenarios == ["sweep"]:  # cosim bench sweep: throughput per worker count
        args.runs = 200 if args.runs is None else args.runs
        return bench_sweep(args)
    args.runs = 5 if args.runs is None else args.runs
    if not 1 <= args.runs <= 1000:
        print(f"cosim: --runs: {args.runs} is not a whole number in 1..1000", file=sys.stderr)
        return 2
    ratio = None
    for name in args.scenarios:
        # Held inputs for the master that compares with the minimal loop (which holds);
        # the master with linear and quadratic extrapolation (the default) on lines of
        # their own.
        scenario = replace(load_scenario(_scenario_path(name)), input_extrapolation="hold")
        cases = {
            "minimal FMPy loop": (scenario, lambda s: _Timed(s, minimal_loop)),
            "master": (scenario, Master),
            "master, linear extrapolation": (replace(scenario, input_extrapolation="linear"),
                                             Master),
            "master, quadratic extrapolation": (
                replace(scenario, input_extrapolation="quadratic"), Master),
        }
        medians = {label: _median_per_step(s, make, args.runs)
                   for label, (s, make) in cases.items()}
        print(f"{name}: {scenario.steps} steps of {scenario.step_size} s, median over "
              f"{args.runs} runs of the stepping loop, per step:")
        for label, median in medians.items():
            print(f"  {label:28s} {1e6 * median:7.1f} us")
        if ratio is None:
            ratio = medians["master"] / medians["minimal FMPy loop"]
    print_container_lines(_scenario_path(args.scenarios[0]), args.runs)
    if args.sweep_runs > 0:
        sweep_throughput(args.sweep_runs)
    print(f"master/minimal ratio: {ratio:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
