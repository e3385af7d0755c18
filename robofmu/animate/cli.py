"""``cosim animate RESULT.csv [options]``: the robot of a run drawn moving, as a GIF
(and MP4 when ffmpeg is on PATH and --mp4 is given). Exit 0 when written, 2 on bad input
(one line on stderr naming the file, the field and the fix)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..cli import entry
from ..errors import output_path
from .errors import AnimateError
from .geometry import PARAMETERS
from .make import DEFAULT_FMU, make_animation


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = ("Draw the 3-PSS robot of a run moving (base, actuators, legs, "
                          "platform, the planned platform as a dashed ghost, end stops in "
                          "red) and write RESULT.gif (docs/animation.md).")
    parser.add_argument("csv", type=Path, help="result CSV of a run (cosim run writes "
                        "results/NAME.csv)")
    parser.add_argument("--out", type=output_path, default=Path("results"),
                        help="folder for NAME.gif (and NAME.mp4) (default: results)")
    parser.add_argument("--fmu", type=Path, help="the Pss3Plant FMU whose parameters drew "
                        f"the run (default: the scenario's, else {DEFAULT_FMU})")
    parser.add_argument("--scenario", type=Path, help="the run's scenario: its plant FMU "
                        "and plant parameters")
    parser.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                        help="a plant geometry parameter in SI units, over the FMU's and the "
                        f"scenario's (repeatable; one of {', '.join(PARAMETERS)})")
    parser.add_argument("--plant", help="the plant's alias in the CSV (default: the first "
                        "with theta[1..3])")
    parser.add_argument("--planner", help="the planner's alias in the CSV (default: the "
                        "first with q[1..3])")
    parser.add_argument("--frames", type=int, default=40, help="pictures, spread evenly "
                        "over the run (default: 40)")
    parser.add_argument("--fps", type=float, default=10.0, help="frames per second "
                        "(default: 10)")
    parser.add_argument("--size", type=int, default=360, help="width and height in pixels "
                        "(default: 360)")
    parser.add_argument("--mp4", action="store_true", help="also write NAME.mp4 (needs "
                        "ffmpeg on PATH)")


def run(args: argparse.Namespace) -> int:
    try:
        summary, written = make_animation(
            args.csv, args.out, fmu=args.fmu, scenario=args.scenario, params=args.param,
            plant=args.plant, planner=args.planner, frames=args.frames, fps=args.fps,
            size=args.size, mp4=args.mp4)
    except AnimateError as e:
        if getattr(args, "debug", False):
            raise
        print(f"cosim: {e}", file=sys.stderr)
        return 2
    print(f"{args.csv.stem}: {summary} -> {', '.join(map(str, written))}")
    return 0


def main(argv=None) -> int:
    """``python -m robofmu.animate ...``: ``cosim animate ...`` (robofmu.cli)."""
    return entry("animate", argv)
