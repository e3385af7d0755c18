"""Linear input extrapolation for the FMI 3.0 builds through the intermediate update
(robofmu/intermediate.py) against the FMI 2.0 builds' input derivatives: the same model
code behind two front-ends. FMI 2.0 integrates the ramp u_k + u'_k s exactly; the FMI 3.0
plant and PID take the ramp's value at the middle of each of their 10 sub-intervals (the
midpoint rule, exact for a ramp) except the first, held at u_k: an input-integral error
of u' d^2 / 2 with d = h / 10, a hundredth of the held input's u' h^2 / 2. Expected: the
two runs differ by less than a twentieth of what separates held from extrapolated
inputs, and the difference is first order in h."""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.fmi3 import open_fmi3  # noqa: E402
from robofmu.master import Master  # noqa: E402
from robofmu.scenario import parse_document  # noqa: E402

SCENARIO = ROOT / "scenarios" / "regulation.toml"


def theta(h: float, extrapolation: str, fmi3: bool) -> np.ndarray:
    document = tomllib.loads(SCENARIO.read_text())
    document["step_size"] = f"{h!r} s"
    document["input_extrapolation"] = extrapolation
    options = {"open_fmu": open_fmi3} if fmi3 else {}
    result = Master(parse_document(document, SCENARIO.parent), **options).run()
    return np.array([result.columns[f"plant.theta[{i}]"] for i in (1, 2, 3)])


def test_fmi3_intermediate_update_follows_the_fmi2_input_slopes():
    gaps = {}
    for h in (1e-3, 5e-4):
        fmi2 = theta(h, "linear", False)
        gaps[h] = np.abs(theta(h, "linear", True) - fmi2).max()
        if h == 1e-3:
            held = np.abs(theta(h, "hold", False) - fmi2).max()
            assert gaps[h] < held / 20, (gaps[h], held)
            # Held inputs: the FMI 3.0 run is the FMI 2.0 run (no callback passed).
            assert np.array_equal(theta(h, "hold", True), theta(h, "hold", False))
    assert 1.6 < gaps[1e-3] / gaps[5e-4] < 2.8, gaps
