"""The initialization dependencies of Planner, PID, ComputedTorque and Pss3Plant (FMI 2.0 ModelStructure
InitialUnknowns, FMI 3.0 <InitialUnknown dependencies>) against finite differences at
initialization (initial_probe.py): each known is moved in Initialization Mode, in
several configurations chosen to make every path of the models act (a tilted moving
plant with every input set, each end stop engaged, the pose from the actuators; the
PID with and without rate inputs, limits and derivative gain; the computed-torque law
off its plan at a tilted moving pose, free and on either limit of each axis; the
planner inside its motion).

- Sound, both standards, every element: an initial unknown that moves lists the known.
- Exact, FMI 3.0 (arrays, where each known and unknown is one variable): every listed
  known moves the unknown in at least one configuration. Per element (FMI 2.0) the
  configurations would have to put every actuator on both of its stops; the lists of
  both standards come from the same declarations. Exempt: unknowns that the knowns
  move only across a switch (the plant's end-stop flags atStop, the PID's conditional
  integration dI/dt, and the computed-torque law's), which a small move does not cross.
Without dependencies an importer must assume every start value depends on every input
(OMSimulator then reports an algebraic loop plant/pid, issue 21)."""

import pytest

from conftest import fmu3_path, fmu_path
from initial_probe import InitialProbe

PLANT_INPUTS = {"actuatorForce": [20.0, -5.0, 12.0], "torqueCommand": [1.0, -2.0, 0.5],
                "generalizedForceCommand": [0.5, 1.0, -1.0],
                "disturbanceTorque": [0.2, -0.3, 0.1]}
MOVING = {"omega0": [0.3, -0.5, 0.8]}
PID_INPUTS = {"measurement": [0.2, 0.1, 0.3], "setpointRate": [0.5, 0.4, 0.3],
              "measuredRate": [0.1, 0.2, -0.1], "feedforward": [0.1, 0.2, 0.3],
              "integral": [0.3, -0.2, 0.1], "filter": [0.05, -0.03, 0.02]}
# Off the plan (the default setpoint), tilted and turning, every input and the integral
# set; the raw outputs are then (8.2, 2.6, -105) N m, and with the accelerations of
# CT_REVERSED (-582, -594, 518) N m: limits of 1 N m hold each axis on both of its limits.
CT_INPUTS = {"setpointRate": [0.05, -0.04, 0.03], "setpointAcceleration": [0.2, 0.1, -0.3],
             "measurement": [0.01, -0.02, 2.37], "measuredRate": [0.03, 0.02, -0.05],
             "integral": [0.002, -0.001, 0.003]}
CT_REVERSED = {**CT_INPUTS, "setpointAcceleration": [-3000.0, -3000.0, 3000.0]}
CT_LIMITED = {"limitOutput": [True] * 3, "uMin": [-1.0] * 3, "uMax": [1.0] * 3}
CONFIGS = {
    "ComputedTorque": [
        CT_INPUTS,
        {**CT_INPUTS, **CT_LIMITED},
        {**CT_REVERSED, **CT_LIMITED},
    ],
    "Pss3Plant": [
        # Tilted and turning, every input set.
        {"theta0": [0.05, -0.04, 2.35], **MOVING, **PLANT_INPUTS},
        # Actuator 1 1.2 mm beyond its upper stop (the pose of l = (152, 77, 77) mm
        # tilted 1 % further), then actuator 2 beyond its lower one (l2 = 2 mm, 2 %).
        {"theta0": [-0.0523, 0.0872, 2.5214], **MOVING},
        {"theta0": [0.0678, 0.1119, 2.3359], **MOVING},
        # The pose from the actuators (forward kinematics).
        {"initFromActuators": [True], "l0": [0.1, 0.077, 0.06], **MOVING, **PLANT_INPUTS},
    ],
    "PID": [
        PID_INPUTS,
        {**PID_INPUTS, "limitOutput": [True] * 3, "setpoint": [5.0, -5.0, 5.0]},
        {**PID_INPUTS, "useRateInputs": [True] * 3},
        {**PID_INPUTS, "useRateInputs": [True] * 3, "Tf": [0.0] * 3},
        {**PID_INPUTS, "Kd": [0.0] * 3},
    ],
    "Planner": [
        {},
        # Start time 0 inside the motion, every boundary value set.
        {"t0": [-0.5], "tf": [1.0], "q0": [0.1, 0.2, 0.3], "qf": [0.5, -0.3, 0.8],
         "qdot0": [0.1, -0.1, 0.2], "qdotf": [0.2, 0.1, -0.2],
         "qddot0": [0.3, 0.2, 0.1], "qddotf": [-0.1, 0.2, 0.3]},
    ],
}
SWITCHED = {"Pss3Plant": ("atStop",), "PID": ("der(integral",),
            "ComputedTorque": ("der(integral",), "Planner": ()}


def observed(probe, model):
    """{unknown: knowns that moved it in some configuration}."""
    union = {name: set() for name in probe.declared()}
    for config in CONFIGS[model]:
        moved, _ = probe.moved(config)
        for name, knowns in moved.items():
            union[name] |= knowns
    return union


@pytest.mark.parametrize("fmi3", [False, True], ids=["fmi2", "fmi3"])
@pytest.mark.parametrize("model", sorted(CONFIGS))
def test_initial_dependencies_match_finite_differences(tmp_path, model, fmi3):
    path = fmu3_path(model) if fmi3 else fmu_path(model)
    probe = InitialProbe(path, tmp_path / model, fmi3)
    declared = probe.declared()
    moved = observed(probe, model)
    probe.close()
    assert [name for name, d in declared.items() if d is None] == []
    undeclared = {name: sorted(moved[name] - d) for name, d in declared.items()
                  if moved[name] - d}
    assert undeclared == {}
    if fmi3:
        unobserved = {name: sorted(d - moved[name]) for name, d in declared.items()
                      if d - moved[name] and not name.startswith(SWITCHED[model])}
        assert unobserved == {}
