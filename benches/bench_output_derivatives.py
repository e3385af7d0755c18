"""What Pss3Plant's output derivatives cost through FMPy (FMI 2.0 Co-Simulation).

Per repetition and per FMU given (both started tilted and moving, driven by constant
actuator forces, and set back to their start every 50 steps) (a "before" and an "after" build, interleaved so that
the load of a shared machine falls on both alike): one fmi2DoStep of 1 ms, then, each
timed on its own, fmi2GetRealOutputDerivatives of gravityCompensation[1..3] order 1
(what the master asks every step), of theta[1..3] and omega[1..3] order 1, of all Real
outputs order 1 and order 2, and the same gravityCompensation request a second time
at the same point. Prints the medians per FMU and the ratios after / before, and
whether both FMUs gave the same bits for every derivative.
Usage: .venv/bin/python benches/bench_output_derivatives.py [BEFORE.fmu] AFTER.fmu
(one FMU: its figures alone).
"""

import shutil
import statistics
import sys
import tempfile
import time

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

REPETITIONS = 400
STEP = 1e-3
# Back to the start every RESTART repetitions (50 ms of the motion, far from the end
# stops).
RESTART = 50


class Plant:
    """An initialized Pss3Plant slave, tilted, moving, driven by constant actuator forces."""

    def __init__(self, path, directory):
        md = read_model_description(path)
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.outputs = [v.valueReference for v in md.modelVariables
                        if v.causality == "output" and v.type == "Real"]
        unzipped = extract(path, unzipdir=directory)
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                             modelIdentifier=md.coSimulation.modelIdentifier,
                             instanceName="bench")
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.setReal(self.refs("theta0") + self.refs("omega0"),
                         [0.05, -0.04, 2.35, 0.3, -0.5, 0.8])
        self.fmu.setReal(self.refs("actuatorForce"), [2.0, -0.5, 1.2])
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.start = self.fmu.getFMUstate()
        self.time = 0.0
        self.medians = {}
        self.values = []

    def refs(self, *names):
        return [self.vr[f"{name}[{i}]"] for name in names for i in (1, 2, 3)]

    def requests(self):
        """(label, value references, order) of the timed requests."""
        gravity = self.refs("gravityCompensation")
        return [
            ("gravityCompensation[1..3] order 1", gravity, 1),
            ("  the same again (same point)", gravity, 1),
            ("theta[1..3] + omega[1..3] order 1", self.refs("theta", "omega"), 1),
            (f"all {len(self.outputs)} outputs order 1", self.outputs, 1),
            (f"all {len(self.outputs)} outputs order 2", self.outputs, 2),
        ]

    def repetition(self):
        """One step and every request, each timed; the values kept."""
        if len(self.values) % (RESTART * self.per_repetition()) == 0:
            self.fmu.setFMUstate(self.start)
            self.time = 0.0
        times = {}
        start = time.perf_counter()
        self.fmu.doStep(self.time, STEP)
        times["fmi2DoStep of 1 ms"] = time.perf_counter() - start
        self.time += STEP
        for label, refs, order in self.requests():
            start = time.perf_counter()
            values = self.fmu.getRealOutputDerivatives(refs, [order] * len(refs))
            times[label] = time.perf_counter() - start
            self.values.extend(values)
        for label, seconds in times.items():
            self.medians.setdefault(label, []).append(seconds)

    def per_repetition(self):
        return sum(len(refs) for _, refs, _ in self.requests())

    def close(self):
        self.fmu.freeFMUstate(self.start)
        self.fmu.terminate()
        self.fmu.freeInstance()


def main(paths):
    directory = tempfile.mkdtemp()
    try:
        plants = [Plant(path, f"{directory}/{k}") for k, path in enumerate(paths)]
        for _ in range(REPETITIONS):
            for plant in plants:
                plant.repetition()
        for plant in plants:
            plant.close()
    finally:
        shutil.rmtree(directory, ignore_errors=True)
    print(f"medians of {REPETITIONS} interleaved repetitions, us: "
          + " | ".join(paths) + (" | after/before" if len(paths) == 2 else ""))
    for label in plants[0].medians:
        medians = [statistics.median(p.medians[label]) * 1e6 for p in plants]
        ratio = f"  {medians[1] / medians[0]:.2f}" if len(medians) == 2 else ""
        print(f"  {label:36}" + "".join(f"{m:9.1f}" for m in medians) + ratio)
    if len(plants) == 2:
        same = plants[0].values == plants[1].values
        print(f"every derivative bit-identical: {'yes' if same else 'NO'} "
              f"({len(plants[0].values)} values)")


if __name__ == "__main__":
    if not 1 <= len(sys.argv[1:]) <= 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
