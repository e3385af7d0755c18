"""The animation of a run (``cosim animate``, robofmu.write_animation): the robot drawn
from a result CSV, the plant's geometry from its FMU, a scenario and overrides."""

from __future__ import annotations

import math
from pathlib import Path

from ..errors import CosimError, require
from ..scenario import ScenarioError, load_scenario
from .errors import COMMAND_LINE, AnimateError
from .geometry import PARAMETERS, robot
from .motion import read_motion
from .plant import plant_parameters

DEFAULT_FMU = Path("dist/Pss3Plant.fmu")
MAX_PICTURE_BYTES = 1_000_000_000


def _check_options(frames: int, fps: float, size: int) -> None:
    if frames < 1:
        raise AnimateError(COMMAND_LINE, "--frames", f"{frames} frames; give 1 or more")
    if not (math.isfinite(fps) and 0.1 <= fps <= 100.0):
        raise AnimateError(COMMAND_LINE, "--fps", f"{fps}; give 0.1 to 100")
    if not 64 <= size <= 4000:
        raise AnimateError(COMMAND_LINE, "--size", f"{size} px; give 64 to 4000")
    memory = frames * size**2 * 3  # the frames are kept as RGB until written
    if memory > MAX_PICTURE_BYTES:
        raise AnimateError(COMMAND_LINE, "--frames", f"{frames} frames of {size} "
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


def _plant(scenario_file: Path | None, fmu_file: Path | None, params: list[str], alias: str):
    """The plant FMU and its parameter overrides: the scenario's, then --fmu, --param."""
    fmu, overrides = fmu_file, {}
    if scenario_file is not None:
        try:
            scenario = load_scenario(scenario_file)
        except (ScenarioError, CosimError, OSError) as e:
            why = str(e).removeprefix(f"{scenario_file}: ")
            raise AnimateError(str(scenario_file), "scenario", f"{why}; fix it or leave "
                               "--scenario out") from None
        if alias not in scenario.fmus:
            raise AnimateError(str(scenario_file), f"fmus.{alias}", "no such FMU; name the "
                               "plant's alias with --plant")
        fmu = fmu or scenario.fmus[alias]
        overrides.update(scenario.parameters.get(alias, {}))
    overrides.update(_user_params(params))
    return Path(fmu or DEFAULT_FMU), overrides


def make_animation(csv: Path, out: Path, *, fmu: Path | None = None,
                   scenario: Path | None = None, params: list[str] | None = None,
                   plant: str | None = None, planner: str | None = None, frames: int = 40,
                   fps: float = 10.0, size: int = 360, mp4: bool = False
                   ) -> tuple[str, list[Path]]:
    """Draws the run of the result CSV `csv` and writes NAME.gif (and NAME.mp4 with
    `mp4`) into the folder `out`: (its summary, the files written). The arguments are
    those of ``cosim animate`` (`params`: its --param NAME=VALUE); AnimateError for bad
    input, named as the command line names it."""
    _check_options(frames, fps, size)
    require("matplotlib", "plots", "cosim animate")
    require("PIL", "plots", "cosim animate")
    from .render import render_run, write_outputs  # matplotlib and Pillow: the extra 'plots'
    from .writer import ffmpeg
    motion = read_motion(csv, plant, planner)
    plant_fmu, overrides = _plant(scenario, fmu, list(params or []), motion.plant)
    rob = robot(plant_parameters(plant_fmu, overrides))
    if mp4:
        ffmpeg()
    animation = render_run(rob, motion, frames, size, title=csv.stem)
    written = write_outputs(animation, out / csv.stem, fps, mp4)
    return animation.summary(), list(written)
