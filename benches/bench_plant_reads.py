"""Time to read every output of the Pss3Plant FMU after a co-simulation step.

Benchmark of issue 10 (values computed once per change, not per read): after each
fmi2DoStep the script reads all Real outputs with ONE fmi2GetReal call and with one call
per output (as a master that reads signal by signal does), and prints the medians over
the repetitions, and the median time of the step itself (values computed eagerly at
the end of a step are paid there). Usage: .venv/bin/python benches/bench_plant_reads.py [dist/Pss3Plant.fmu]
"""

import statistics
import sys
import time

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


def main(path="dist/Pss3Plant.fmu", repetitions=400, step=1e-3):
    md = read_model_description(path)
    outputs = [v.valueReference for v in md.modelVariables
               if v.causality == "output" and v.type == "Real"]
    unzipped = extract(path)
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bench")
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    t = 0.0
    one_call, per_output, steps = [], [], []
    for _ in range(repetitions):
        start = time.perf_counter()
        fmu.doStep(t, step)
        steps.append(time.perf_counter() - start)
        t += step
        start = time.perf_counter()
        fmu.getReal(outputs)
        one_call.append(time.perf_counter() - start)
        fmu.doStep(t, step)
        t += step
        start = time.perf_counter()
        for vr in outputs:
            fmu.getReal([vr])
        per_output.append(time.perf_counter() - start)
    fmu.terminate()
    fmu.freeInstance()
    print(f"{len(outputs)} Real outputs, {repetitions} repetitions")
    print(f"fmi2DoStep of {step} s: median {statistics.median(steps) * 1e6:.1f} us")
    print(f"one fmi2GetReal of all outputs after a step: median "
          f"{statistics.median(one_call) * 1e6:.1f} us")
    print(f"one fmi2GetReal per output after a step: median "
          f"{statistics.median(per_output) * 1e6:.1f} us")


if __name__ == "__main__":
    main(*sys.argv[1:2])
