"""Pss3Plant keeps its output derivatives along the local motion for the point
(parameters, state, inputs) they were evaluated at. Through both standards (FMPy's
FMU2Slave and FMU3Slave, FMI 3.0 with arrays): after an input changes or a step, an
instance that has answered before gives the bits of a twin that never asked before
(two instances stepped alike hold the same state bit for bit)."""

import pytest

from test_output_derivatives import PlantCalls

NEW_FORCES = [-3.0, 8.0, 1.0]


def set_forces(plant, forces):
    if plant.fmi3:
        plant.fmu.setFloat64([plant.fmu.vr["actuatorForce"]], forces)
    else:
        plant.fmu.setReal([plant.vr[f"actuatorForce[{i}]"] for i in (1, 2, 3)], forces)


def both_orders(plant):
    return plant.derivatives(1) + plant.derivatives(2)


def twin(directory, fmi3, steps_after_input):
    """Both orders of a plant moved like the asked one that asks only at the end."""
    plant = PlantCalls(directory, fmi3)
    plant.step(0.0, 0.02)
    set_forces(plant, NEW_FORCES)
    if steps_after_input:
        plant.step(0.02, 0.01)
    derivatives = both_orders(plant)
    plant.close()
    return derivatives


@pytest.mark.parametrize("fmi3", [False, True], ids=["fmi2", "fmi3"])
def test_changed_inputs_and_steps_give_the_answer_of_a_twin_that_never_asked(tmp_path,
                                                                              fmi3):
    # Expected: the derivatives of a twin instance moved alike that asks only once,
    # at the point compared (nothing stored from another point).
    asked = PlantCalls(tmp_path / "asked", fmi3)
    asked.step(0.0, 0.02)
    before = both_orders(asked)
    assert both_orders(asked) == before  # the same point asked twice
    set_forces(asked, NEW_FORCES)
    after_input = both_orders(asked)
    assert after_input != before  # the input changes the answer
    assert after_input == twin(tmp_path / "twin1", fmi3, False)
    asked.step(0.02, 0.01)
    after_step = both_orders(asked)
    assert after_step != after_input
    assert after_step == twin(tmp_path / "twin2", fmi3, True)
    asked.close()
