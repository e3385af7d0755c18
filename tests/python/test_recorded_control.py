"""The master's CSV records the control the plant receives (issue 21): on every row of
the regulation scenario the recorded pid.u equals the plant's input read back at the same
moment, and the plant alone, driven by the recorded pid.u held over each step, retraces
the recorded motion bit for bit (the truth: the applied control is the one that moves
the plant)."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from robofmu.fmi2 import FmuInstance  # noqa: E402
from robofmu.master import Master  # noqa: E402
from robofmu.scenario import Signal, load_scenario  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
AXES = (1, 2, 3)


def test_recorded_control_is_the_applied_control():
    scenario = load_scenario(ROOT / "scenarios" / "regulation.toml")
    # Held inputs: the plant receives the recorded value over the whole step (with
    # linear extrapolation it receives the recorded value at the step's start plus a
    # slope, which the replay below would have to pass too).
    scenario.input_extrapolation = "hold"
    scenario.record += [Signal("plant", f"generalizedForceCommand[{i}]") for i in AXES]
    result = Master(scenario).run()
    u = [result.columns[f"pid.u[{i}]"] for i in AXES]
    applied = [result.columns[f"plant.generalizedForceCommand[{i}]"] for i in AXES]
    assert u == applied
    # Replay: the plant alone, its input set to row k's pid.u over step k.
    plant = FmuInstance("plant", scenario.fmus["plant"], scenario.start_time,
                        scenario.stop_time)
    try:
        for name, value in scenario.parameters["plant"].items():
            plant.set_value(name, value)
        plant.enter_initialization()
        names = tuple(f"generalizedForceCommand[{i}]" for i in AXES)
        plant.set_values(names, [column[0] for column in u])
        plant.exit_initialization()
        theta = tuple(f"theta[{i}]" for i in AXES)
        h = scenario.step_size
        worst = 0.0
        for k in range(scenario.steps):
            plant.set_values(names, [column[k] for column in u])
            plant.do_step(scenario.start_time + k * h, h)
            replayed = plant.get_values(theta)
            worst = max(worst, *(abs(replayed[j] - result.columns[f"plant.theta[{i}]"][k + 1])
                                 for j, i in enumerate(AXES)))
    finally:
        plant.close()
    assert worst == 0.0
