"""Time to instantiate and free one instance of each FMU, FMI 2.0 and FMI 3.0.

Benchmark of issue 10 (instantiation cost of the per-instance variable tables): per FMU
and standard, the median time of one fmi2Instantiate + fmi2FreeInstance (Co-Simulation)
or fmi3InstantiateCoSimulation + fmi3FreeInstance pair, called through ctypes with the
arguments prepared once (the library stays loaded). With several dist directories
(e.g. a baseline build and the current one) the runs alternate between them round by
round, so that both see the same machine load; the last column is each directory's
median over the first one's.

Usage: .venv/bin/python benches/bench_instantiate.py [--rounds 20] [--calls 200] [dist ...]
(default dist: dist; FMI 3.0 FMUs are read from <dist>/fmi3/).
"""

import argparse
import ctypes
import statistics
import time
from pathlib import Path

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave, defaultCallbacks, fmi2CoSimulation
from fmpy.fmi3 import (FMU3Slave, fmi3Boolean, fmi3InstanceEnvironment,
                       fmi3IntermediateUpdateCallback, fmi3LogMessageCallback,
                       fmi3ValueReference)

# One FMU per checked-in modelDescription/<Model>.xml: adding an FMU changes no list here.
DESCRIPTIONS = Path(__file__).resolve().parents[1] / "modelDescription"
MODELS = sorted(path.stem for path in DESCRIPTIONS.glob("*.xml"))


def load(path, slave_class):
    """The model description, the unzipped directory and the loaded Co-Simulation FMU."""
    md = read_model_description(path)
    unzipped = extract(path)
    fmu = slave_class(guid=md.guid, unzipDirectory=unzipped,
                      modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bench")
    return md, unzipped, fmu


class Fmi2Pair:
    """fmi2Instantiate + fmi2FreeInstance of one FMI 2.0 FMU."""

    def __init__(self, path):
        md, unzipped, self.fmu = load(path, FMU2Slave)
        resources = Path(unzipped, "resources").as_uri().encode()
        self.args = (b"bench", fmi2CoSimulation, md.guid.encode(), resources,
                     ctypes.byref(defaultCallbacks), 0, 0)

    def once(self):
        component = self.fmu.fmi2Instantiate(*self.args)
        if not component:
            raise RuntimeError("fmi2Instantiate failed")
        self.fmu.fmi2FreeInstance(component)


class Fmi3Pair:
    """fmi3InstantiateCoSimulation + fmi3FreeInstance of one FMI 3.0 FMU."""

    def __init__(self, path):
        md, unzipped, self.fmu = load(path, FMU3Slave)
        self.log = fmi3LogMessageCallback(lambda *args: None)
        self.update = fmi3IntermediateUpdateCallback()
        no_variables = (fmi3ValueReference * 0)()
        resources = (str(Path(unzipped, "resources")) + "/").encode()
        false = fmi3Boolean(False)
        self.args = (b"bench", md.guid.encode(), resources, false, false, false, false,
                     no_variables, 0, fmi3InstanceEnvironment(), self.log, self.update)

    def once(self):
        instance = self.fmu.fmi3InstantiateCoSimulation(*self.args)
        if not instance:
            raise RuntimeError("fmi3InstantiateCoSimulation failed")
        self.fmu.fmi3FreeInstance(instance)


def timed(pair, calls):
    """Seconds per instantiate + free pair, one per call."""
    times = []
    for _ in range(calls):
        start = time.perf_counter()
        pair.once()
        times.append(time.perf_counter() - start)
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dists", nargs="*", default=["dist"])
    parser.add_argument("--rounds", type=int, default=20)
    parser.add_argument("--calls", type=int, default=200)
    args = parser.parse_args()
    cases = [(model, standard) for model in MODELS for standard in ("2.0", "3.0")]
    pairs = {}
    for dist in args.dists:
        for model, standard in cases:
            if standard == "2.0":
                pairs[dist, model, standard] = Fmi2Pair(f"{dist}/{model}.fmu")
            else:
                pairs[dist, model, standard] = Fmi3Pair(f"{dist}/fmi3/{model}.fmu")
    times = {key: [] for key in pairs}
    for key, pair in pairs.items():
        timed(pair, 10)  # warm-up: page faults, allocator arenas
    for _ in range(args.rounds):
        for key, pair in pairs.items():
            times[key].extend(timed(pair, args.calls))
    print(f"instantiate + free, median of {args.rounds * args.calls} pairs, us")
    print(f"{'FMU':10} {'FMI':4} " + " ".join(f"{d:>24}" for d in args.dists)
          + ("   ratio" if len(args.dists) > 1 else ""))
    for model, standard in cases:
        medians = [statistics.median(times[d, model, standard]) * 1e6 for d in args.dists]
        ratio = "".join(f" {m / medians[0]:7.3f}" for m in medians[1:])
        print(f"{model:10} {standard:4} " + " ".join(f"{m:24.1f}" for m in medians) + ratio)


if __name__ == "__main__":
    main()
