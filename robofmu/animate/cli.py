"""``cosim animate RESULT.csv [options]``: the robot of a run drawn moving, as a GIF
(and MP4 when ffmpeg is on PATH and --mp4 is given). Exit 0 when written, 2 on bad input
(one line on stderr naming the file, the field and the fix)."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

from ..cli import entry
from ..errors import CosimError, output_path, require
from ..scenario import ScenarioError, load_scenario
from .errors import COMMAND_LINE, AnimateError
from .geometry import PARAMETERS, robot
from .motion import read_motion
from .plant import plant_parameters

DEFAULT_FMU = Path("dist/Pss3Plant.fmu")
MAX_PICTURE_BYTES = 1_000_000_000


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


def _check_options(args) -> None:
    if args.frames < 1:
        raise AnimateError(COMMAND_LINE, "--frames", f"{args.frames} frames; give 1 or more")
    if not (math.isfinite(args.fps) and 0.1 <= args.fps <= 100.0):
        raise AnimateError(COMMAND_LINE, "--fps", f"{args.fps}; give 0.1 to 100")
    if not 64 <= args.size <= 4000:
        raise AnimateError(COMMAND_LINE, "--size", f"{args.size} px; give 64 to 4000")
    memory = args.frames * args.size**2 * 3  # the frames are kept as RGB until written
    if memory > MAX_PICTURE_BYTES:
        raise AnimateError(COMMAND_LINE, "--frames", f"{args.frames} frames of {args.size} "
                           f"px need {memory / 1e9:.1f} GB; give fewer frames or a smaller "
                           "--size")


def _user_params(pairs: list[str]) -> dict[str, float]:
    values = {}
    for pair in pairs:
        name, sep, text = pair.partition("=")
        if not sep or name not in PARAMETERS:
            raise AnimateError(COMMAND_LINE, f"--param {pair}", "give NAME=VALUE with NAME "
                               f"one of {', '.join(PARAMETERS)}")
        try:
            values[name] = float(text)
        except ValueError:
            raise AnimateError(COMMAND_LINE, f"--param {pair}", f"'{text}' is not a "
                               "number; give the value in SI units (m, rad)") from None
    return values


def _plant(args, alias: str):
    """The plant FMU and its parameter overrides: the scenario's, then --fmu, --param."""
    fmu, overrides = args.fmu, {}
    if args.scenario is not None:
        try:
            scenario = load_scenario(args.scenario)
        except (ScenarioError, CosimError, OSError) as e:
            why = str(e).removeprefix(f"{args.scenario}: ")
            raise AnimateError(str(args.scenario), "scenario", f"{why}; fix it or leave "
                               "--scenario out") from None
        if alias not in scenario.fmus:
            raise AnimateError(str(args.scenario), f"fmus.{alias}", "no such FMU; name the "
                               "plant's alias with --plant")
        fmu = fmu or scenario.fmus[alias]
        overrides.update(scenario.parameters.get(alias, {}))
    overrides.update(_user_params(args.param))
    return Path(fmu or DEFAULT_FMU), overrides


def make_animation(args: argparse.Namespace) -> tuple[str, list[Path]]:
    """Draws and writes the animation the arguments ask for: (its summary, the files
    written); AnimateError for bad input (the library's robofmu.animate too)."""
    _check_options(args)
    require("matplotlib", "plots", "cosim animate")
    require("PIL", "plots", "cosim animate")
    from .render import render_run, write_outputs  # matplotlib and Pillow: the extra 'plots'
    from .writer import ffmpeg
    motion = read_motion(args.csv, args.plant, args.planner)
    fmu, overrides = _plant(args, motion.plant)
    rob = robot(plant_parameters(fmu, overrides))
    if args.mp4:
        ffmpeg()
    animation = render_run(rob, motion, args.frames, args.size, title=args.csv.stem)
    written = write_outputs(animation, args.out / args.csv.stem, args.fps, args.mp4)
    return animation.summary(), list(written)


def run(args: argparse.Namespace) -> int:
    try:
        summary, written = make_animation(args)
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
