"""The tolerance rules of cosim verify (robofmu/verify/tolerance.py).

The FMI cross-check band rule is checked against the second implementation of the same
definition, FMPy 0.3.32's fmpy.cross_check (validate_signal: the band and the outliers;
validate_result: the verdict), on the same data: our reference signals, perturbed in
several ways and sampled on other time grids. The deviation rule against closed forms."""

import numpy as np
import pytest
from fmpy.cross_check import validate_result, validate_signal

from conftest import REFERENCES
from verify_cli import ROOT  # noqa: F401  (puts the repository on sys.path)
from robofmu.verify.table import read_table
from robofmu.verify.tolerance import CrossCheckBand, Deviation, from_json, from_text

# FMPy's validate_signal imports from scipy.ndimage.filters (deprecated in SciPy 1.17).
pytestmark = pytest.mark.filterwarnings(
    "ignore:Please import .* from the `scipy.ndimage` namespace:DeprecationWarning")


def reference_signals():
    """(time, values, start, stop) of a few reference columns and two constants."""
    signals = []
    for case, column in [("Planner/defaults", "q[1]"), ("Planner/defaults", "qddot[3]"),
                         ("PID/saturation", "u[1]"), ("Pss3Plant/path1", "theta[3]")]:
        folder = REFERENCES / case
        table = read_table(next(folder.glob("*_ref.csv")))
        signals.append((table.time, table.columns[column], table.time[0], table.time[-1]))
    t = np.linspace(0.0, 2.0, 201)
    signals.append((t, np.zeros_like(t), 0.0, 2.0))
    signals.append((t, np.full_like(t, -3.0), 0.0, 2.0))
    return signals


def perturbations(t, y, rng):
    """Results on other grids: shifted in time, offset, noisy, partly wrong."""
    span = max(np.ptp(y), 1.0)
    grid = np.linspace(t[0], t[-1], 737)
    base = np.interp(grid, t, y)
    yield grid, base
    yield grid, np.interp(grid - 0.03 * (t[-1] - t[0]), t, y)
    yield grid, base + 0.08 * span
    yield grid, base + 0.12 * span * rng.standard_normal(len(grid))
    wrong = base.copy()
    wrong[len(grid) // 2:] += span
    yield grid, wrong


@pytest.mark.parametrize("index", range(6))
def test_band_rule_is_fmpys_cross_check_rule(index):
    t_ref, y_ref, start, stop = reference_signals()[index]
    rng = np.random.default_rng(index)
    rule = CrossCheckBand()
    verdicts = []
    for t, y in perturbations(t_ref, y_ref, rng):
        t_band, y_min, y_max, fmpy_outside = validate_signal(
            t=t, y=y, t_ref=t_ref.copy(), y_ref=y_ref, t_start=start, t_stop=stop)
        limits = rule.limits(t, t_ref, y_ref, start, stop)
        np.testing.assert_array_equal(limits.plot_time, t_band)
        np.testing.assert_allclose(limits.plot_lower, y_min, rtol=0, atol=1e-15)
        np.testing.assert_allclose(limits.plot_upper, y_max, rtol=0, atol=1e-15)
        ours = (y < limits.lower) | (y > limits.upper)
        np.testing.assert_array_equal(ours, fmpy_outside)
        result = np.zeros(len(t), dtype=[("time", float), ("y", float)])
        result["time"], result["y"] = t, y
        reference = np.zeros(len(t_ref), dtype=[("time", float), ("y", float)])
        reference["time"], reference["y"] = t_ref, y_ref
        fmpy_passes = validate_result(result, reference, start, stop) is None
        assert rule.passes(ours) == fmpy_passes
        verdicts.append(fmpy_passes)
    # The data exercise both verdicts: the unperturbed result passes, the half-wrong fails.
    assert verdicts[0] and not verdicts[-1]


def test_deviation_rule_absolute_and_relative_to_the_range():
    # Closed form: y = sin t on [0, pi] has range 1 (t = pi/2 is a sample), so
    # Deviation(0, 0.01) is a band of 0.01 and Deviation(1e-3, 0.01) one of 0.011.
    t = np.linspace(0.0, np.pi, 101)
    y = np.sin(t)
    for rule, width in [(Deviation(0.01), 0.01), (Deviation(0.0, 0.01), 0.01),
                        (Deviation(1e-3, 0.01), 0.011)]:
        assert rule.width(t, y, 0.0, np.pi) == pytest.approx(width, rel=1e-12)
        for offset, outside in [(0.999 * width, False), (1.001 * width, True)]:
            limits = rule.limits(t, t, y, 0.0, np.pi)
            shifted = y + offset
            flags = (shifted < limits.lower) | (shifted > limits.upper)
            assert flags.all() == outside and rule.passes(flags) != outside
    # The range counts only the experiment: on [0, pi/2] sin t spans 1 as well, on
    # [0, pi/6] it spans 1/2 (interpolated end at pi/6 between samples).
    assert Deviation(0, 1).width(t, y, 0.0, np.pi / 6) == pytest.approx(0.5, abs=1e-3)


def test_rule_specifications():
    assert from_json(1e-4) == Deviation(1e-4)
    assert from_json({"rel": 0.02}) == Deviation(0.0, 0.02)
    assert from_json({"abs": 1e-3, "rel": 0.02}) == Deviation(1e-3, 0.02)
    assert from_json("cross-check") == CrossCheckBand()
    assert from_text("1e-4,0.02") == Deviation(1e-4, 0.02)
    assert from_text("cross-check") == CrossCheckBand()
    for bad in (-1.0, float("nan"), True, "tight", {"abs": 1, "relative": 2}, {}):
        with pytest.raises(ValueError):
            from_json(bad)
    for bad in ("", "1,2,3", "x", "-1"):
        with pytest.raises(ValueError):
            from_text(bad)
