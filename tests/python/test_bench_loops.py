"""The loops that python -m robofmu.bench times compute the closed loop (a benchmark of a
wrong loop would mislead): the minimal FMPy loop is our master's sampled coupling with
nothing else, so it ends on the master's state to rounding; the container run ends within
the container-master bound of test_container.py."""

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.bench_container import container_run, minimal_run  # noqa: E402
from robofmu.container import build_container  # noqa: E402
from robofmu.master import Master  # noqa: E402
from robofmu.scenario import load_scenario  # noqa: E402


def test_benchmarked_loops_end_where_the_master_ends(tmp_path):
    scenario = load_scenario(ROOT / "scenarios" / "three_axis_quintic.toml")
    scenario.input_extrapolation = "hold"  # the loops below hold their inputs
    master = Master(scenario).run()
    theta = [f"plant.theta[{i}]" for i in (1, 2, 3)]
    expected = np.array([master.columns[name][-1] for name in theta])
    minimal = minimal_run(scenario)
    assert np.allclose([minimal[name] for name in theta], expected, atol=1e-12, rtol=0)
    container = tmp_path / "loop.fmu"
    build_container(scenario, container)
    stepped = container_run(scenario, container)
    # test_container.py: |container - master| on theta <= 1.2e-6 rad on this scenario.
    assert np.allclose([stepped[name] for name in theta], expected, atol=1.2e-6, rtol=0)
