"""``cosim examples [--path NAME]``: the bundled example scenarios (they name the bundled
FMUs) and the reference cases of ``cosim verify`` (robofmu.bundle), one line each: kind,
name, path; with ``--path NAME`` only that one's path
(``cosim run $(cosim examples --path regulation)``,
``cosim verify $(cosim fmus --path PID) $(cosim examples --path PID/defaults)``)."""

from __future__ import annotations

import argparse

from . import bundle
from .errors import ScenarioError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--path", metavar="NAME",
                        help="print only this one's path (a scenario such as regulation, or "
                        "a reference case such as PID/defaults)")


def run(args: argparse.Namespace) -> int:
    rows = [("scenario", name, path) for name, path in bundle.scenarios().items()]
    rows += [("reference", name, path) for name, path in bundle.references().items()]
    if args.path is not None:
        paths = {name: path for _, name, path in rows}
        if args.path not in paths:
            raise ScenarioError(f"--path: '{args.path}' is neither a bundled scenario nor a "
                                "reference case; 'cosim examples' lists them")
        print(paths[args.path])
        return 0
    if not rows:
        raise ScenarioError("no examples: neither an installed wheel nor a checkout")
    width = max(len(name) for _, name, _ in rows)
    for kind, name, path in rows:
        print(f"{kind:<9}  {name:<{width}}  {path}")
    return 0
