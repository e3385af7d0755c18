"""``cosim fmus [--path NAME]``: the bundled FMUs (robofmu.bundle), one line each: the name
a scenario uses (``plant = "Pss3Plant"``), the FMI version, the model's version and the
path; with ``--path NAME`` only that FMU's path, for other tools
(``fmpy info $(cosim fmus --path PID)``)."""

from __future__ import annotations

import argparse
import zipfile
from pathlib import Path
from xml.etree import ElementTree

from . import bundle
from .errors import ScenarioError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--path", metavar="NAME",
                        help="print only this FMU's path (a name of the list: PID, fmi3/PID)")


def attributes(path: Path) -> dict[str, str]:
    """The root attributes of the FMU's modelDescription.xml."""
    with zipfile.ZipFile(path) as z:
        return dict(ElementTree.fromstring(z.read("modelDescription.xml")).attrib)


def run(args: argparse.Namespace) -> int:
    fmus = bundle.fmus()
    if args.path is not None:
        if args.path not in fmus:
            raise ScenarioError(f"--path: '{args.path}' is not a bundled FMU "
                                f"({bundle.where_fmus_come_from()}); name one of those")
        print(fmus[args.path])
        return 0
    if not fmus:
        raise ScenarioError(f"no FMUs: {bundle.where_fmus_come_from()}")
    width = max(len(name) for name in fmus)
    for name, path in fmus.items():
        a = attributes(path)
        print(f"{name:<{width}}  FMI {a.get('fmiVersion', '?'):<3}  "
              f"version {a.get('version', '?'):<8}  {path}")
    return 0
