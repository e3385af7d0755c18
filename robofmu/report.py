"""Metrics and plots of closed-loop results (planner -> PID -> 3-PSS plant).

Results are read by column name ("alias.variable"), so the same code serves the
master's results and the Rust reference CSVs. Angles are converted to degrees for
people only here.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import require

AXES = ("thx", "thy", "thz")


def read_csv(path: Path) -> dict[str, np.ndarray]:
    """A cross-check CSV as {column name: values}."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    names = rows[0]
    data = np.array(rows[1:], dtype=float)
    return {name: data[:, k] for k, name in enumerate(names)}


def vector(result: dict, alias: str, name: str) -> np.ndarray:
    """The three columns alias.name[1..3] as an (n, 3) array."""
    return np.stack([result[f"{alias}.{name}[{i}]"] for i in (1, 2, 3)], axis=1)


def sig(x: float, digits: int = 4) -> str:
    """`x` with `digits` significant digits (1.234e-05, 0.01234, 123.4, 1.234e+05):
    fixed decimals would print a small error as 0.00000."""
    return f"{x:.{digits}g}"


@dataclass
class Metrics:
    rms_error_deg: float
    max_error_deg: float
    peak_force_n: float
    peak_planned_acceleration: float  # rad/s^2
    peak_angular_acceleration: float  # rad/s^2, plant omega_dot

    def si(self) -> dict[str, float]:
        """The metrics in SI (rad, N, rad/s^2), keyed as robofmu.limits names them."""
        return {"rms_error": math.radians(self.rms_error_deg),
                "max_error": math.radians(self.max_error_deg),
                "peak_force": self.peak_force_n,
                "peak_planned_acceleration": self.peak_planned_acceleration,
                "peak_angular_acceleration": self.peak_angular_acceleration}

    def row(self) -> list[str]:
        return [sig(self.rms_error_deg), sig(self.max_error_deg), sig(self.peak_force_n),
                sig(math.degrees(self.peak_planned_acceleration)),
                sig(math.degrees(self.peak_angular_acceleration))]


HEADER = ["RMS error (deg)", "max error (deg)", "peak |f| (N)",
          "peak planned accel (deg/s^2)", "peak |omega_dot| (deg/s^2)"]


def metrics(result: dict) -> Metrics:
    """Tracking metrics over the run. The peak accelerations leave out the last sample:
    path 1 ends at the stroke end at 75 mm/s, where the end stop engages at t = tf."""
    error = vector(result, "planner", "q") - vector(result, "plant", "theta")
    norm = np.linalg.norm(error, axis=1)
    return Metrics(
        rms_error_deg=math.degrees(float(np.sqrt(np.mean(norm ** 2)))),
        max_error_deg=math.degrees(float(np.abs(error).max())),
        peak_force_n=float(np.abs(vector(result, "plant", "force")).max()),
        peak_planned_acceleration=float(np.abs(vector(result, "planner", "qddot")[:-1]).max()),
        peak_angular_acceleration=float(np.abs(vector(result, "plant", "omegaDot")[:-1]).max()),
    )


# The smallest span a panel shows, in the panel's unit: data that vary less (round-off,
# 1e-14 deg) are drawn flat with a note instead of being magnified into a deviation.
MIN_SPAN = {"deg": 1e-6, "N": 1e-6, "SI units": 1e-6}


def steady_axis(ax, values, unit: str) -> None:
    """Keeps `ax` from autoscaling a spread below MIN_SPAN[unit] into a full panel."""
    values = np.asarray(values, dtype=float)
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return
    low, high = float(finite.min()), float(finite.max())
    floor = MIN_SPAN.get(unit, 0.0)
    if high - low < floor:
        centre = 0.5 * (low + high)
        ax.set_ylim(centre - floor, centre + floor)
        ax.ticklabel_format(axis="y", useOffset=False, style="plain")
        ax.text(0.01, 0.04, f"constant to within {high - low:.1e} {unit} (round-off scale; "
                f"panel spans {2 * floor:g} {unit})", transform=ax.transAxes, fontsize=7)


def coincide_note(a, b, unit: str, span: float) -> str:
    """A legend note when two plotted lines coincide to within 0.2 % of the panel."""
    gap = float(np.nanmax(np.abs(np.asarray(a) - np.asarray(b))))
    if gap <= 2e-3 * max(span, MIN_SPAN.get(unit, 0.0)):
        return f" (coincides with planned: max |diff| = {gap:.1e} {unit})"
    return ""


def hidden_labels(series: list, labels: list[str], unit: str, span: float) -> list[str]:
    """`labels`, each of a line that a later-drawn one covers (within 0.5 % of the
    panel's span, about a line's width) saying which and how close: identical curves
    would otherwise hide one another without a word."""
    tol = 5e-3 * max(span, MIN_SPAN.get(unit, 0.0))
    out = []
    for i, line in enumerate(series):
        gaps = [(float(np.nanmax(np.abs(np.asarray(line) - np.asarray(series[j])))), labels[j])
                for j in range(i + 1, len(series))]
        covered = [(gap, label) for gap, label in gaps if gap <= tol]
        if covered:
            gap, label = covered[-1]
            out.append(f"{labels[i]} (hidden under {label}: "
                       + ("equal)" if gap == 0.0 else f"within {gap:.1g} {unit})"))
        else:
            out.append(labels[i])
    return out


def _figure(rows: int):
    # lazy: matplotlib.pyplot is 0.4 s of start-up (benches/bench_startup.py), paid by plots only
    matplotlib = require("matplotlib", "plots", "the plots of a run")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(rows, 1, figsize=(8, 2.4 * rows), sharex=True, squeeze=False)
    return plt, fig, axes[:, 0]


def plot_tracking(result: dict, name: str, out_dir: Path,
                  reference: dict | None = None) -> list[Path]:
    """Orientation and reference, tracking error and actuator forces of one run."""
    t = result["time"]
    q = np.degrees(vector(result, "planner", "q"))
    theta = np.degrees(vector(result, "plant", "theta"))
    written = []
    plt, fig, axes = _figure(3)
    for i, ax in enumerate(axes):
        span = float(np.ptp(np.concatenate([q[:, i], theta[:, i]])))
        ax.plot(t, q[:, i], "--", color="gray", label="planned")
        ax.plot(t, theta[:, i], label="plant (co-simulation)"
                + coincide_note(q[:, i], theta[:, i], "deg", span))
        steady_axis(ax, np.concatenate([q[:, i], theta[:, i]]), "deg")
        if reference is not None:
            ax.plot(reference["time"], np.degrees(reference[f"plant.theta[{i + 1}]"]), ".",
                    markersize=3, label="Rust reference (ODE)")
        ax.set_ylabel(f"{AXES[i]} (deg)")
        ax.grid(True)
        ax.legend(loc="best", fontsize=7)
    axes[0].set_title(f"{name}: orientation and planned motion")
    axes[-1].set_xlabel("time (s)")
    written.append(out_dir / f"{name}_orientation.png")
    fig.tight_layout()
    fig.savefig(written[-1], dpi=110)
    plt.close(fig)

    plt, fig, axes = _figure(2)
    error, force = q - theta, vector(result, "plant", "force")
    error_labels = hidden_labels([error[:, i] for i in range(3)], list(AXES), "deg",
                                 float(np.ptp(error)))
    force_labels = hidden_labels([force[:, i] for i in range(3)],
                                 [f"actuator {i + 1}" for i in range(3)], "N",
                                 float(np.ptp(force)))
    for i in range(3):
        axes[0].plot(t, error[:, i], label=error_labels[i])
        axes[1].plot(t, force[:, i], label=force_labels[i])
    steady_axis(axes[0], error, "deg")
    steady_axis(axes[1], force, "N")
    axes[0].set_ylabel("error q - theta (deg)")
    axes[0].set_title(f"{name}: tracking error (planned q minus plant theta) and actuator "
                      "forces", fontsize=10)
    axes[1].set_ylabel("actuator force (N)")
    axes[1].set_xlabel("time (s)")
    for ax in axes:
        ax.grid(True)
        # Beside the panel: a legend never covers a curve.
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    written.append(out_dir / f"{name}_error_forces.png")
    fig.set_size_inches(10, 4.8)
    fig.tight_layout()
    fig.savefig(written[-1], dpi=110)
    plt.close(fig)
    return written


def plot_cubic_vs_quintic(cubic: dict, quintic: dict, motion: str, out_dir: Path) -> Path:
    """Planned Euler-angle accelerations (left) and the plant's angular acceleration in
    the base frame (right) of both planners."""
    # lazy: matplotlib.pyplot is 0.4 s of start-up (benches/bench_startup.py), paid by plots only
    matplotlib = require("matplotlib", "plots", "the plots of a run")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 2, figsize=(11, 7), sharex=True)
    for i in range(3):
        for label, r, color in (("cubic", cubic, "C0"), ("quintic", quintic, "C1")):
            axes[i, 0].plot(r["time"], np.degrees(r[f"planner.qddot[{i + 1}]"]), color=color,
                            label=label)
            axes[i, 1].plot(r["time"][:-1], np.degrees(r[f"plant.omegaDot[{i + 1}]"][:-1]),
                            color=color, label=label)
        axes[i, 0].set_ylabel(f"{AXES[i]}'' planned (deg/s^2)")
        axes[i, 1].set_ylabel(f"omega_dot_{'xyz'[i]} plant (deg/s^2)")
        for ax in axes[i]:
            ax.grid(True)
    axes[0, 0].set_title(f"{motion}: planned Euler-angle acceleration")
    axes[0, 1].set_title("plant angular acceleration (base frame)")
    axes[0, 0].legend(loc="best", fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("time (s)")
    path = out_dir / f"{motion}_cubic_vs_quintic_acceleration.png"
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def format_table(header: list[str], rows: list[list[str]]) -> str:
    widths = [max(len(r[k]) for r in [header, *rows]) for k in range(len(header))]

    def line(r: list[str]) -> str:
        return "  ".join(c.rjust(w) if k else c.ljust(w) for k, (c, w) in enumerate(zip(r, widths)))

    return "\n".join([line(header), line(["-" * w for w in widths]), *map(line, rows)])
