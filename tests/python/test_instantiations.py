"""How many times each FMU is instantiated before the first step of a run: reading a
scenario (its checks against the FMUs: parameters, workspace, input-derivative probes)
and the run share one co-simulation instance per FMU (robofmu.instances). Counted by
wrapping FMPy's FMU2Slave.instantiate and FMU2Model.instantiate, where the harness
instantiates FMI 2.0 FMUs; the stepping itself instantiates nothing (plan switches
reset), so a whole load and run counts the instantiations before its first step.
Before issue 40: the plant 8 (co-simulation) + 2 (Model Exchange), the planner 4, the
PID 4 for the regulation."""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

import pytest
from fmpy.fmi2 import FMU2Model, FMU2Slave

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

import robofmu  # noqa: E402
from robofmu import design, instances, slopes  # noqa: E402


# Each FMU's co-simulation instance once; the plant's Model Exchange instance once too:
# the gain design linearises it at rest at every design pose (robofmu.design).
ONCE = {"Planner CS": 1, "PID CS": 1, "Pss3Plant CS": 1, "Pss3Plant ME": 1}


@pytest.fixture
def counted(monkeypatch):
    counts: Counter = Counter()
    for kind, cls in (("CS", FMU2Slave), ("ME", FMU2Model)):
        def instantiate(self, *args, _original=cls.instantiate, _kind=kind, **kwargs):
            counts[f"{self.modelIdentifier} {_kind}"] += 1
            return _original(self, *args, **kwargs)

        monkeypatch.setattr(cls, "instantiate", instantiate)
    # Nothing kept from an earlier test: no idle instance, no cached answer of an FMU.
    instances.close_all()
    design._INERTIA.clear()
    slopes.accepted.cache_clear()
    slopes.served.cache_clear()
    yield counts
    instances.close_all()


@pytest.mark.parametrize("name", ["regulation", "path1_quintic", "three_axis_waypoints"])
def test_each_fmu_is_instantiated_once_before_the_first_step(counted, name):
    scenario = robofmu.load(name)
    result = robofmu.simulate(scenario)
    assert len(result.time) > 1
    assert dict(counted) == ONCE
    # A second run of the loaded scenario instantiates nothing (the shared instances).
    again = robofmu.simulate(scenario)
    assert dict(counted) == ONCE
    for column in result.names:  # and computes the same, bit for bit
        assert (again[column] == result[column]).all(), column


def test_the_command_line_instantiates_each_fmu_once(counted, tmp_path):
    from robofmu.cli import main
    assert main(["run", str(robofmu.example("regulation")), "--out", str(tmp_path),
                 "--quiet", "--no-plots"]) == 0
    assert dict(counted) == ONCE
