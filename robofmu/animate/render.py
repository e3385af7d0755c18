"""A run rendered: its frames, their pictures, and the files written from them."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .draw import Canvas
from .errors import AnimateError
from .frames import Frame, make_frames
from .geometry import Robot
from .motion import Motion
from .writer import ffmpeg, gif_to, mp4_to


@dataclass(frozen=True)
class Animation:
    """The frames of a run and their RGB pictures, in order."""

    frames: list[Frame]
    pictures: list[np.ndarray]

    def summary(self) -> str:
        """One line: frames, time span and the first frame where each end stop shows."""
        first, last = self.frames[0].time, self.frames[-1].time
        hits: dict[tuple[int, int], float] = {}  # (leg, side) -> first time at the stop
        for frame in self.frames:
            for leg, side in enumerate(frame.stops):
                if side:
                    hits.setdefault((leg + 1, int(side)), frame.time)
        stops = ", ".join(f"leg {leg} {'lower' if side < 0 else 'upper'} at {t:.3f} s"
                          for (leg, side), t in sorted(hits.items(), key=lambda h: h[1]))
        return (f"{len(self.frames)} frames, t = {first:.3f} .. {last:.3f} s; end stops: "
                f"{stops or 'none'}")


def render_run(rob: Robot, motion: Motion, frames: int, size: int, title: str) -> Animation:
    """Renders `frames` pictures of `size` x `size` pixels of `motion`."""
    chosen = make_frames(rob, motion, frames)
    canvas = Canvas(rob, size, title)
    return Animation(frames=chosen, pictures=[canvas.render(f) for f in chosen])


def write_outputs(animation: Animation, stem: Path, fps: float, mp4: bool) -> list[Path]:
    """Writes STEM.gif (and STEM.mp4); returns the paths written."""
    gif = stem.parent / f"{stem.name}.gif"
    try:
        stem.parent.mkdir(parents=True, exist_ok=True)
        gif_to(gif, animation.pictures, fps)
        if not mp4:
            return [gif]
        video = stem.parent / f"{stem.name}.mp4"
        mp4_to(video, animation.pictures, fps, ffmpeg())
        return [gif, video]
    except OSError as e:
        raise AnimateError(str(stem.parent), "--out", f"cannot write there ({e.strerror}); "
                           "give a writable folder") from None
