"""What libcosim and ecos do with our FMI 3.0 builds (dist/fmi3), the evidence behind the
"no" entries of docs/interoperability.md. Each test pins an importer's behaviour: when a
new version of the importer fails one, the matrix must change.

Truth for the values: FMPy, which reads the arrays with nValues = 3."""

import numpy as np
from fmpy import simulate_fmu

from conftest import fmu3_path
from importer_runs import quiet


def test_libcosim_refuses_fmi3_with_a_reason():
    # libcosim 0.11.2 loads FMI 1.0 and 2.0 only: the slave is not created and the
    # reason is in its last error message (libcosimpy does not check the NULL pointer:
    # adding such a slave to an execution crashes the process).
    from libcosimpy._internal import get_last_error_message
    from libcosimpy.CosimSlave import CosimLocalSlave
    quiet()
    slave = CosimLocalSlave(fmu_path=fmu3_path("Planner"), instance_name="planner")
    assert not slave.ptr()
    assert "Unsupported FMI version" in get_last_error_message()


def test_ecos_reads_an_fmi3_array_wrongly_and_hides_the_error():
    # ecos 0.7.2 ignores <Dimension>: it offers the array q as one Real "q" and calls
    # fmi3GetFloat64 with nValues = 1. Our FMU answers fmi3Error ("nValues = 1, but the
    # variables have 3 elements", logged at ecos's debug level only) and, as FMI 3.0
    # requires after an Error, refuses every later call but the reset/free ones. ecos
    # raises nothing: get_real returns whatever its buffer held (0.0 here), later steps
    # fail unnoticed and even the time then reads wrong. FMPy reads q = (0.25, -0.15,
    # 0.4) rad at t = 1 s (the default plan, halfway from 0 to (0.5, -0.3, 0.8) rad).
    from ecospy.EcosSimulation import EcosSimulation
    from ecospy.EcosSimulationStructure import EcosSimulationStructure
    quiet()
    fmu = fmu3_path("Planner")
    truth = simulate_fmu(fmu, fmi_type="CoSimulation", stop_time=1.0, step_size=0.01,
                         output_interval=0.01, output=["q"])["q"][-1]
    assert np.allclose(truth, [0.25, -0.15, 0.4], atol=1e-12)
    structure = EcosSimulationStructure()
    structure.add_model("planner", fmu)
    with EcosSimulation(structure=structure, step_size=0.01) as sim:
        assert sim.init()
        sim.step(100)
        q = sim.get_real("planner::q")
        assert np.abs(truth - q).min() > 0.1, q
        sim.step(1)  # the instance is in the Error state: the step is refused
        assert abs(sim.get_real("planner::time") - 1.01) > 1e-3
