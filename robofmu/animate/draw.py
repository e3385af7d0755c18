"""Draws one frame in 3D with matplotlib's Agg backend and returns its RGB pixels."""

from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from .frames import Frame
from .geometry import Robot, rails

BASE, RAIL, SLIDER, LEG = "0.35", "0.6", "navy", "tab:orange"
PLATFORM, GHOST, STOP = "tab:blue", "tab:green", "red"
# Pictures this wide or wider get tick labels and a caption.
DETAILED_PX = 300


class Canvas:
    """A square figure of `size` pixels with fixed limits for `rob`, redrawn per frame."""

    def __init__(self, rob: Robot, size: int, title: str):
        self.rob, self.size, self.title = rob, size, title
        self.figure = Figure(figsize=(size / 100, size / 100), dpi=100)
        self.canvas = FigureCanvasAgg(self.figure)
        self.axes = self.figure.add_subplot(projection="3d")
        reach = np.max(np.linalg.norm(rails(rob)[:, :, :2], axis=2))
        top = rob.pivot[2] + rob.params["ld"]
        self.limits = (1.1 * reach, top)
        if size < DETAILED_PX:
            self.figure.subplots_adjust(left=0.0, right=1.0, bottom=0.0, top=0.86)
        else:
            self.figure.subplots_adjust(left=0.0, right=0.92, bottom=0.04, top=0.88)
            self.figure.text(0.02, 0.98, "blue: platform\ngreen dashed: planned\n"
                             "red X: end stop", fontsize=6, va="top")
        self._set_up_axes()
        _draw_base(self.axes, rob)
        self.static = (len(self.axes.lines), len(self.axes.collections))

    def _set_up_axes(self) -> None:
        ax, (reach, top) = self.axes, self.limits
        ax.set_xlim(-reach, reach)
        ax.set_ylim(-reach, reach)
        ax.set_zlim(0.0, top)
        # Without axes there is room to zoom in on the robot; with them, the box is drawn
        # smaller so that the x-axis label and ticks stay inside the frame.
        zoom = 1.3 if self.size < DETAILED_PX else 0.86
        ax.set_box_aspect((1.0, 1.0, top / (2.0 * reach)), zoom=zoom)
        ax.view_init(elev=22, azim=-60)
        if self.size < DETAILED_PX:
            ax.set_axis_off()
        else:
            ax.set_xlabel("x, m", fontsize=7)
            ax.set_ylabel("y, m", fontsize=7)
            ax.set_zlabel("z, m", fontsize=7)
            ax.tick_params(labelsize=6)

    def render(self, frame: Frame) -> np.ndarray:
        """The frame's pixels, (size, size, 3) uint8: the base stays, the rest is redrawn."""
        ax = self.axes
        lines, collections = self.static
        for artist in [*ax.lines[lines:], *ax.collections[collections:]]:
            artist.remove()
        _draw_robot(ax, self.rob, frame)
        if frame.ghost is not None:
            _draw_platform(ax, self.rob, frame.ghost, frame.ghost_rotation, ghost=True)
        self._caption(frame)
        self.canvas.draw()
        return np.asarray(self.canvas.buffer_rgba())[:, :, :3].copy()

    def _caption(self, frame: Frame) -> None:
        small = self.size < DETAILED_PX
        text = f"t = {frame.time:.3f} s"
        for side, name in ((-1, "strokeMin"), (1, "strokeMax")):
            legs = [str(i + 1) for i, s in enumerate(frame.stops) if s == side]
            if legs:
                text += f"\nat {name}: leg {' '.join(legs)}"
        self.axes.set_title(text if small else f"{self.title}   {text}",
                            fontsize=6 if small else 8, loc="center" if small else "right")


def _segment(ax, a, b, **style):
    ax.plot(*np.column_stack([a, b]), **style)


def _draw_base(ax, rob: Robot) -> None:
    origin = np.zeros(3)
    _segment(ax, origin, rob.pivot, color=BASE, lw=2.5)  # the central column to P
    for i in range(3):
        _segment(ax, origin, rob.h[i], color=BASE, lw=1.0)
    ring = np.vstack([rob.h, rob.h[:1]])  # the base's slider joints at l = 0
    ax.plot(*ring.T, color=BASE, lw=1.0)
    for leg, (lo, hi) in enumerate(rails(rob)):
        _segment(ax, lo, hi, color=RAIL, lw=4.0, solid_capstyle="butt")
        ax.text(*(hi + 0.04 * rob.u[leg]), str(leg + 1), fontsize=7, color=BASE)


def _draw_robot(ax, rob: Robot, frame: Frame) -> None:
    p = frame.pose
    for i in range(3):
        _segment(ax, p.sliders[i], p.platform[i], color=LEG, lw=1.8)
        stop = frame.stops[i] != 0
        ax.plot(*p.sliders[i], marker="X" if stop else "o", ms=7 if stop else 4,
                color=STOP if stop else SLIDER, linestyle="none")
    _draw_platform(ax, rob, p.platform, p.rotation, ghost=False)


def _draw_platform(ax, rob: Robot, joints, rot, ghost: bool) -> None:
    color = GHOST if ghost else PLATFORM
    if not ghost:
        ax.add_collection3d(Poly3DCollection([joints], facecolor=color, alpha=0.45,
                                             edgecolor=color))
    else:
        closed = np.vstack([joints, joints[:1]])
        ax.plot(*closed.T, color=color, lw=1.2, linestyle="--")
    normal = rob.pivot + 0.5 * rob.params["ld"] * rot[:, 2]
    _segment(ax, rob.pivot, normal, color=color, lw=1.2, linestyle="--" if ghost else "-")
    first = rob.pivot + 0.8 * (joints[0] - rob.pivot)  # marks leg 1's side: shows the roll
    _segment(ax, rob.pivot, first, color=color, lw=1.0, linestyle="--" if ghost else "-")
