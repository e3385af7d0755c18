"""Plots of a sweep's table, written next to it: each metric over the varied grid
(a line for one varying quantity, a heat map for two; averaged over the random draws)
and, with random samples, a histogram of each metric."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

PLOTTED = {"rms_error_deg": "RMS tracking error (deg)", "max_error_deg": "max error (deg)",
           "peak_force_n": "peak actuator force (N)", "settling_time_s": "settling time (s)",
           "wall_s": "wall time per run (s)"}


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _finite(rows, metric) -> bool:
    return any(isinstance(r.get(metric), float) and math.isfinite(r[metric]) for r in rows)


def _mean_over(rows, keys, metric) -> dict:
    groups: dict = {}
    for r in rows:
        if isinstance(r.get(metric), float):
            groups.setdefault(tuple(r[k] for k in keys), []).append(r[metric])
    return {k: float(np.mean(v)) for k, v in groups.items()}


def plot_sweep(header: list[str], rows: list[dict], axes: list[str], random: bool,
               out: Path, name: str) -> list[Path]:
    """`axes`: the grid and workspace columns; returns the files written."""
    ok = [r for r in rows if r.get("status") == "ok"]
    metrics = [m for m in PLOTTED if _finite(ok, m)]
    if not ok or not metrics:
        return []
    varying = [a for a in axes if len({r[a] for r in ok}) > 1]
    written = []
    if varying:
        written.append(_grid_plot(ok, varying, metrics, out / f"{name}_grid.png"))
    if random:
        written.append(_histograms(ok, metrics, varying, out / f"{name}_histogram.png"))
    return written


def _panels(count: int, height: float):
    plt = _plt()
    columns = min(count, 3)
    rows = -(-count // columns)
    fig, panels = plt.subplots(rows, columns, figsize=(4.4 * columns, height * rows),
                               squeeze=False)
    for ax in panels.flat[count:]:
        ax.set_visible(False)
    return plt, fig, panels.flat


def _grid_plot(rows, varying, metrics, path: Path) -> Path:
    plt, fig, panels = _panels(len(metrics), 3.6)
    for ax, metric in zip(panels, metrics):
        if len(varying) == 2:
            xs = sorted({r[varying[0]] for r in rows})
            ys = sorted({r[varying[1]] for r in rows})
            means = _mean_over(rows, varying[:2], metric)
            image = np.array([[means.get((x, y), np.nan) for x in xs] for y in ys])
            mesh = ax.pcolormesh(xs, ys, image, shading="nearest")
            fig.colorbar(mesh, ax=ax)
            ax.set_ylabel(varying[1])
        else:
            means = _mean_over(rows, varying[:1], metric)
            xs = sorted(k[0] for k in means)
            ax.plot(xs, [means[(x,)] for x in xs], "o-")
            ax.set_ylabel(PLOTTED[metric])
        ax.set_xlabel(varying[0])
        ax.set_title(PLOTTED[metric], fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _histograms(rows, metrics, varying, path: Path) -> Path:
    """One histogram per metric over the random draws. With grid points, each run's
    value is taken relative to the median of its grid point (the spread the random
    quantities cause), in percent."""
    groups: dict = {}
    for r in rows:
        groups.setdefault(tuple(r[a] for a in varying), []).append(r)
    relative = len(groups) > 1
    series = {}
    for metric in metrics:
        if metric == "wall_s":
            continue
        values = []
        for members in groups.values():
            x = np.array([r[metric] for r in members if isinstance(r.get(metric), float)])
            x = x[np.isfinite(x)]
            if relative and len(x):
                median = float(np.median(x))
                x = 100.0 * (x / median - 1.0) if median != 0.0 else x * 0.0
            values += list(x)
        if values:
            series[metric] = values
    plt, fig, panels = _panels(max(len(series), 1), 3.4)
    for ax, (metric, values) in zip(panels, series.items()):
        ax.hist(values, bins=max(5, min(30, len(values) // 3)))
        ax.set_xlabel(PLOTTED[metric] + (": % from the grid point's median"
                                         if relative else ""), fontsize=8)
        ax.set_ylabel("runs")
    fig.suptitle(f"Monte Carlo over the random draws ({len(rows)} runs"
                 + (f", {len(groups)} grid points)" if relative else ")"), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
