"""Plots of a sweep's table, written next to it: each metric over the varied grid, with
the spread over the random draws (a line for one varying quantity: the median and a band
from the 10th to the 90th percentile of the draws, their range when there are fewer than
10, every draw as a dot; a heat map of the median for two) and, with at least
MIN_HISTOGRAM_DRAWS draws per grid point, a histogram of each metric."""

from __future__ import annotations

import math
from collections import Counter
from pathlib import Path

import numpy as np

from ..errors import require

PLOTTED = {"rms_error_deg": "RMS tracking error (deg)", "max_error_deg": "max error (deg)",
           "peak_force_n": "peak actuator force (N)", "settling_time_s": "settling time (s)",
           "wall_s": "wall time per run (s)"}
PERCENTILES = (10.0, 90.0)
MIN_PERCENTILE_DRAWS = 10  # fewer draws: the band is their range
MIN_HISTOGRAM_DRAWS = 20  # fewer draws per grid point: no histogram


def _plt():
    # lazy: matplotlib.pyplot is 0.4 s of start-up (benches/bench_startup.py), paid by plots only
    matplotlib = require("matplotlib", "plots", "the plots of a sweep")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _finite(rows, metric) -> bool:
    return any(isinstance(r.get(metric), float) and math.isfinite(r[metric]) for r in rows)


def _values_over(rows, keys, metric) -> dict:
    groups: dict = {}
    for r in rows:
        if isinstance(r.get(metric), float) and math.isfinite(r[metric]):
            groups.setdefault(tuple(r[k] for k in keys), []).append(r[metric])
    return groups


def spread(rows, keys, metric) -> dict:
    """Per grid point (the values of `keys`): (median, low, high, draws) of the metric
    over the random draws; low/high the PERCENTILES, or the range below
    MIN_PERCENTILE_DRAWS draws."""
    out = {}
    for key, values in _values_over(rows, keys, metric).items():
        x = np.array(values)
        if len(x) >= MIN_PERCENTILE_DRAWS:
            low, high = np.percentile(x, PERCENTILES)
        else:
            low, high = x.min(), x.max()
        out[key] = (float(np.median(x)), float(low), float(high), len(x))
    return out


def plot_sweep(header: list[str], rows: list[dict], axes: list[str], random: bool,
               out: Path, name: str, about: str = "") -> list[Path]:
    """`axes`: the grid and workspace columns; `about`: the sweep's title (its name,
    what is drawn at random and how); returns the files written."""
    ok = [r for r in rows if r.get("status") == "ok"]
    metrics = [m for m in PLOTTED if _finite(ok, m)]
    if not ok or not metrics:
        return []
    varying = [a for a in axes if len({r[a] for r in ok}) > 1]
    written = []
    if varying:
        written.append(_grid_plot(ok, varying, metrics, out / f"{name}_grid.png",
                                  about or name))
    if random and min(Counter(tuple(r[a] for a in varying) for r in ok).values()) >= \
            MIN_HISTOGRAM_DRAWS:
        written.append(_histograms(ok, metrics, varying, out / f"{name}_histogram.png",
                                   about or name))
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


SAME = 1e-9  # relative: a metric that varies less is "the same in every run"
SMALL = 0.01  # relative spread below which a panel's axis is widened (see _unmagnified)


def _unit(metric: str) -> str:
    return PLOTTED[metric].rsplit("(", 1)[1].rstrip(")")


def _constant(rows, metric) -> float | None:
    """The metric's value when it is the same in every run (to SAME), else None."""
    values = [r[metric] for r in rows if isinstance(r.get(metric), float)
              and math.isfinite(r[metric])]
    low, high = min(values), max(values)
    return values[0] if high - low <= SAME * max(abs(low), abs(high)) else None


def _why_constant(rows, metric) -> str:
    """Why a metric can be the same in every run (the regulation's start offset)."""
    regulation = any(isinstance(r.get("settling_time_s"), float)
                     and math.isfinite(r["settling_time_s"]) for r in rows)
    if metric == "max_error_deg" and regulation:
        return ("\nthe start offset of the regulation (it starts away from its setpoint),\n"
                "not a tracking error: see the RMS error and the settling time")
    return ""


def _unmagnified(ax, values, unit: str) -> None:
    """A spread below SMALL of the values' magnitude is drawn on an axis of +-5 % of the
    median, with a note, instead of filling the panel (0.6 % would look as large as
    the error panels' factor of two)."""
    x = np.asarray([v for v in values if math.isfinite(v)])
    median = float(np.median(x))
    if median == 0.0 or np.ptp(x) >= SMALL * abs(median):
        return
    ax.set_ylim(median - 0.05 * abs(median), median + 0.05 * abs(median))
    ax.text(0.02, 0.04, f"spread {100 * np.ptp(x) / abs(median):.2g} % of the median; "
            "axis +-5 %", transform=ax.transAxes, fontsize=7)


def _grid_plot(rows, varying, metrics, path: Path, about: str) -> Path:
    plt, fig, panels = _panels(len(metrics), 3.6)
    for ax, metric in zip(panels, metrics):
        same = _constant(rows, metric)
        if same is not None and metric != "wall_s":
            ax.text(0.5, 0.5, f"{same:.4g} {_unit(metric)} in every run"
                    + _why_constant(rows, metric), ha="center", va="center",
                    transform=ax.transAxes, fontsize=8)
            ax.set_xticks([])
            ax.set_yticks([])
            ax.set_title(PLOTTED[metric], fontsize=9)
            continue
        stats = spread(rows, varying[:2], metric)
        draws = max(n for *_, n in stats.values())
        if len(varying) == 2:
            xs = sorted({k[0] for k in stats})
            ys = sorted({k[1] for k in stats})
            image = np.array([[stats[(x, y)][0] if (x, y) in stats else np.nan for x in xs]
                              for y in ys])
            mesh = ax.pcolormesh(xs, ys, image, shading="nearest")
            fig.colorbar(mesh, ax=ax)
            ax.set_ylabel(varying[1])
            width = max(high - low for _, low, high, _ in stats.values())
            note = (f"median of {draws} draws; widest band {_band(draws)}: {width:.3g}"
                    if draws > 1 else "")
        else:
            xs = sorted(k[0] for k in stats)
            median = [stats[(x,)][0] for x in xs]
            ax.plot(xs, median, "o-", label=f"median of {draws} draws" if draws > 1 else None)
            if draws > 1:
                ax.fill_between(xs, [stats[(x,)][1] for x in xs], [stats[(x,)][2] for x in xs],
                                alpha=0.25, label=_band(draws))
                dots = _values_over(rows, varying[:1], metric)
                ax.plot([x for x in xs for _ in dots[(x,)]], [v for x in xs for v in dots[(x,)]],
                        ".", color="0.35", markersize=3, label="each draw")
                ax.legend(fontsize=7)
            ax.set_ylabel(PLOTTED[metric])
            _unmagnified(ax, [v for vs in _values_over(rows, varying[:1], metric).values()
                              for v in vs], _unit(metric))
            note = ""
        ax.set_xlabel(varying[0])
        ax.set_title(PLOTTED[metric] + (f"\n{note}" if note else ""), fontsize=9)
    fig.suptitle(about, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _band(draws: int) -> str:
    if draws >= MIN_PERCENTILE_DRAWS:
        return f"{PERCENTILES[0]:.0f}-{PERCENTILES[1]:.0f} percentile"
    return f"range of {draws} draws"


def _histograms(rows, metrics, varying, path: Path, about: str) -> Path:
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
    fig.suptitle(f"{about}\nMonte Carlo over the random draws ({len(rows)} runs"
                 + (f", {len(groups)} grid points)" if relative else ")"), fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
