"""cosim verify on a third-party binary runtime: the closed loop as the container FMU of
fmu-manipulation-toolbox (robofmu.container.build_container), verified against our
master's result of the same scenario (robofmu.master.Master) as the reference CSV, given
by options only (--reference, --step, --tolerance).

The tolerances are test_container.py's coupling bounds (derived there from the loop's
gains: the container's PID integrates the error sampled at the end of each step, the
master's at its start); the deviations cosim verify reports are checked against that
test's own computation of them (a second formulation)."""

import csv

import numpy as np
import pytest

from test_container import deviations, force_after_step, run_master, scenario, tolerances
from robofmu.container import build_container
from verify_cli import verify

AXES = (1, 2, 3)


def write_reference(master: dict, s, path):
    """The master's plant angles and actuator forces under the container's names
    (`plant.theta[i]` is a container local, `force[i]` its output), the forces at the
    moment FMPy samples the container (test_container.force_after_step)."""
    force = force_after_step(master, s)
    columns = {f"plant.theta[{i}]": master[f"plant.theta[{i}]"] for i in AXES}
    columns.update({f"force[{i}]": force[:, i - 1] for i in AXES})
    with open(path, "w", newline="") as f:
        out = csv.writer(f, quoting=csv.QUOTE_NONNUMERIC, lineterminator="\n")
        out.writerow(["time", *columns])
        for k, t in enumerate(master["time"]):
            out.writerow([float(t), *(float(c[k]) for c in columns.values())])
    return list(columns)


def test_container_fmu_verified_against_the_master(tmp_path):
    s = scenario("three_axis_quintic")
    master = run_master(s)
    fmu = tmp_path / "loop.fmu"
    build_container(s, fmu)
    reference = tmp_path / "master.csv"
    signals = write_reference(master, s, reference)
    bound = tolerances(master, s)
    options = []
    for signal in signals:
        kind = "theta" if "theta" in signal else "force"
        options += ["--tolerance", f"{signal}={float(bound[kind])!r}"]
    outcome = verify(fmu, "--reference", reference, "--step", s.step_size,
                     "--out", tmp_path / "out", *options)
    print(outcome.out)
    assert outcome.code == 0, outcome.out + outcome.err
    report = outcome.report(tmp_path / "out")
    assert report["fmi_version"] == "2.0" and report["interface"] == "CoSimulation"
    errors = {entry["signal"]: entry["max_error"] for entry in report["signals"]}
    assert sorted(errors) == sorted(signals)
    # Second formulation: test_container's deviations on FMPy's own run of the container.
    from fmpy import simulate_fmu
    names = [f"{sig}[{i}]" for sig in ("plant.theta", "pid.u", "planner.q") for i in AXES]
    container = simulate_fmu(str(fmu), output=names + [f"force[{i}]" for i in AXES],
                             output_interval=s.step_size, step_size=s.step_size)
    measured = deviations(master, container, s)
    for i in AXES:
        assert errors[f"plant.theta[{i}]"] == pytest.approx(measured["theta"][i - 1], rel=1e-9)
        assert errors[f"force[{i}]"] == pytest.approx(measured["force"][i - 1], rel=1e-9)
    # Not trivially passing: the deviations are far above rounding.
    assert min(errors.values()) > 1e-9 and np.isfinite(list(errors.values())).all()
    # The container is Co-Simulation only: Model Exchange is bad input.
    refused = verify(fmu, "--reference", reference, "--interface", "me",
                     "--out", tmp_path / "me")
    assert refused.code == 2 and "does not support ModelExchange" in refused.err
    assert not (tmp_path / "me").exists()
