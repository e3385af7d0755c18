"""``cosim check SCENARIO [--fmu-dir DIR]``: validates a scenario without simulating:
every field, every parameter against its FMU variable (unit, type, range), the FMUs'
acceptance of their parameters, and (closed loop) the start pose and the whole planned
path against the workspace."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from .errors import output_path
from .expand import expanded_toml
from .run import add_common, fmu_dir
from .scenario import ScenarioError, load_scenario


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common(parser)
    parser.add_argument("--expanded", type=output_path, metavar="FILE.toml",
                        help="also write the expanded (plain, SI) form that the harness "
                        "runs and the Rust reference reads")


def same_file(a: Path, b: Path) -> bool:
    """Whether `a` names the file `b` (a link, another spelling of its path)."""
    try:
        return a.exists() and b.exists() and os.path.samefile(a, b)
    except OSError:
        return a.resolve() == b.resolve()


def run(args: argparse.Namespace) -> int:
    if args.expanded is not None and (args.expanded.suffix != ".toml"
                                      or args.expanded.is_dir()):
        raise ScenarioError(f"--expanded: {args.expanded}: name a .toml file to write")
    if args.expanded is not None and same_file(args.expanded, args.scenario):
        raise ScenarioError(f"--expanded: {args.expanded} is the scenario being checked; name "
                            "another file (e.g. --expanded results/expanded.toml)")
    scenario = load_scenario(args.scenario, fmu_dir(args.fmu_dir))
    if args.expanded is not None:
        args.expanded.parent.mkdir(parents=True, exist_ok=True)
        args.expanded.write_text(expanded_toml(scenario, args.expanded, args.scenario.name))
    fmus = ", ".join(f"{a} = {p.name}" for a, p in scenario.fmus.items())
    print(f"{args.scenario}: ok: '{scenario.name}', {scenario.steps} steps of "
          f"{scenario.step_size:g} s, FMUs {fmus}"
          + (f", {len(scenario.limits)} limits" if scenario.limits else ""))
    return 0
