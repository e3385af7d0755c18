"""What `cosim run` writes under --out for scenario NAME:

- NAME.csv: time and every connected and recorded signal, SI (the cross-check format:
  quoted names on the first line);
- NAME.units.json: the unit of every CSV column as the FMU declares it ("1": none);
- NAME_orientation.png, NAME_error_forces.png (closed loop) or NAME_signals.png;
- NAME_summary.json: the metrics (SI and labelled degrees) and the verdict of every limit
  the scenario declares (robofmu.limits)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .fmu_check import describe, unit_of
from .limits import CLOSED_LOOP_COLUMNS, judge
from .report import _figure, metrics, plot_tracking, steady_axis
from .scenario import Scenario


def column_units(scenario: Scenario, names) -> dict[str, str]:
    units = {"time": "s"}
    for name in names:
        alias, variable = name.split(".", 1)
        md = describe(scenario.fmus[alias], f"fmus.{alias}")
        v = {x.name: x for x in md.modelVariables}.get(variable)
        if v is None:  # a clocked output of an FMU the run ticked (robofmu.clocked)
            v = md.clocked[variable][0]
        declared = unit_of(md, v)
        units[name] = declared[0] if declared else "1"
    return units


def write_outputs(scenario: Scenario, result, out: Path, plots: bool = True) -> dict:
    """Writes the files above; returns {"files": [...], "metrics": {...}, "limits": [...]}."""
    out.mkdir(parents=True, exist_ok=True)
    name = scenario.name
    csv_path = out / f"{name}.csv"
    result.write_csv(csv_path)
    units_path = out / f"{name}.units.json"
    units_path.write_text(json.dumps(column_units(scenario, result.names), indent=1) + "\n")
    files = [csv_path, units_path]
    columns = {"time": np.asarray(result.time)} | {
        n: np.asarray(v) for n, v in result.columns.items()}
    summary: dict = {"scenario": name, "steps": scenario.steps,
                     "step_size_s": scenario.step_size}
    verdicts = []
    if all(c in columns for c in CLOSED_LOOP_COLUMNS):
        m = metrics(columns)
        summary["metrics_si"] = m.si()
        summary["metrics_human"] = {"rms_error_deg": m.rms_error_deg,
                                    "max_error_deg": m.max_error_deg,
                                    "peak_force_N": m.peak_force_n}
        verdicts = judge(scenario.limits, m.si())
        if plots:
            files += plot_tracking(columns, name, out)
    else:
        summary["signals"] = {n: {"min": float(np.min(v)), "max": float(np.max(v))}
                              for n, v in result.columns.items()}
        if plots:
            files.append(plot_signals(columns, result.names, name, out))
    summary["limits"] = [{"limit": n, "measured_si": v, "bound_si": b,
                          "measured": _human(v, u), "bound": _human(b, u), "unit": u,
                          "passed": ok} for n, v, b, u, ok in verdicts]
    summary["passed"] = all(ok for *_, ok in verdicts)
    summary_path = out / f"{name}_summary.json"
    summary_path.write_text(json.dumps(summary, indent=1) + "\n")
    files.append(summary_path)
    summary["files"] = [str(f) for f in files]
    return summary


def _human(value: float, unit: str) -> float:
    return math.degrees(value) if unit == "deg" else value


def plot_signals(columns: dict, names, title: str, out: Path) -> Path:
    """Every recorded signal against time, one panel per FMU (at most 8 lines each)."""
    by_alias: dict[str, list[str]] = {}
    for n in names:
        by_alias.setdefault(n.split(".", 1)[0], []).append(n)
    plt, fig, axes = _figure(len(by_alias))
    for ax, (alias, signals) in zip(axes, by_alias.items()):
        for n in signals[:8]:
            ax.plot(columns["time"], columns[n], label=n)
        steady_axis(ax, np.concatenate([columns[n] for n in signals[:8]]), "SI units")
        ax.set_ylabel(f"{alias} (SI)")
        ax.grid(True)
        ax.legend(loc="best", fontsize=7)
    axes[0].set_title(f"{title}: recorded signals (SI units, see the .units.json)")
    axes[-1].set_xlabel("time (s)")
    path = out / f"{title}_signals.png"
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
