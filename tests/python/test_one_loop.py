"""The master's one stepping loop (robofmu.loop: native code, with callbacks into Python
for every instance that is not an FMI 2.0 FMPy one) against the same loop written out
in Python over FMPy's wrappers (reference_loop.ReferenceMaster, a test oracle only),
bit for bit: every extrapolation order, both couplings, plan switches, step halvings,
FMI 3.0, and a failure's message."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.errors import CosimError  # noqa: E402
from robofmu.fmi3 import open_fmi3  # noqa: E402
from robofmu.master import Master  # noqa: E402
from robofmu.scenario import load_scenario  # noqa: E402
from reference_loop import ReferenceMaster  # noqa: E402


def scenario(name: str, **changes):
    s = load_scenario(ROOT / "scenarios" / f"{name}.toml")
    for key, value in changes.items():
        setattr(s, key, value)
    return s


def same(s, **kw) -> None:
    ours, oracle = Master(s, **kw).run(), ReferenceMaster(s, **kw).run()
    assert ours.columns == oracle.columns
    assert ours.discards == oracle.discards


@pytest.mark.parametrize("coupling", ["sampled", "gauss-seidel"])
@pytest.mark.parametrize("extrapolation", ["hold", "linear", "quadratic"])
def test_the_loop_is_the_python_loop_bit_for_bit(extrapolation, coupling):
    # The waypoint scenario has plan switches, where the runs of steps are split.
    s = scenario("three_axis_waypoints", input_extrapolation=extrapolation, coupling=coupling)
    assert s.schedule
    same(s)


def test_halved_steps_are_the_python_loops_bit_for_bit():
    # The plant's integrator takes at most 100000 internal steps a communication step:
    # with maxStep = 20 ns it discards a 4 ms step (200000) and takes its quarters
    # (50000 each; a half of 100000 is at the limit), from the rolled-back states.
    s = scenario("regulation", max_step_halvings=2, stop_time=0.004, step_size=0.004)
    s.parameters["plant"]["maxStep"] = 2e-8
    ours = Master(s).run()
    assert ours.discards and "retrying with h = 0.002 s" in ours.discards[0]
    same(s)


@pytest.mark.parametrize("extrapolation", ["hold", "quadratic"])
def test_fmi3_runs_through_callbacks_as_the_python_loop(extrapolation):
    same(scenario("regulation", input_extrapolation=extrapolation, stop_time=0.05),
         open_fmu=open_fmi3)


def test_a_failure_is_reported_as_the_python_loop_reports_it():
    # A plant whose integrator may not take the step (maxStep = 1 ns): it discards the
    # first step; the message names the FMU, the time and the FMU's reason.
    s = scenario("regulation")
    s.parameters["plant"]["maxStep"] = 1e-9
    with pytest.raises(CosimError) as ours:
        Master(s).run()
    with pytest.raises(CosimError) as oracle:
        ReferenceMaster(s).run()
    assert str(ours.value) == str(oracle.value)
    assert str(ours.value).startswith("plant discarded the step at t = 0 s")
