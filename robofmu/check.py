"""``cosim check SCENARIO [--fmu-dir DIR]``: validates a scenario without simulating:
every field, every parameter against its FMU variable (unit, type, range), the FMUs'
acceptance of their parameters, and (closed loop) the start pose and the whole planned
path against the workspace."""

from __future__ import annotations

import argparse

from .errors import output_path
from .expand import check_target, write_expanded
from .run import add_common, fmu_dir
from .scenario import load_scenario


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common(parser)
    parser.add_argument("--expanded", type=output_path, metavar="FILE.toml",
                        help="also write the expanded (plain, SI) form that the harness "
                        "runs and the Rust reference reads")


def run(args: argparse.Namespace) -> int:
    if args.expanded is not None:
        check_target(args.expanded, args.scenario)
    scenario = load_scenario(args.scenario, fmu_dir(args.fmu_dir))
    if args.expanded is not None:
        write_expanded(scenario, args.expanded, args.scenario)
    fmus = ", ".join(f"{a} = {p.name}" for a, p in scenario.fmus.items())
    print(f"{args.scenario}: ok: '{scenario.name}', {scenario.steps} steps of "
          f"{scenario.step_size:g} s, FMUs {fmus}"
          + (f", {len(scenario.limits)} limits" if scenario.limits else ""))
    return 0
