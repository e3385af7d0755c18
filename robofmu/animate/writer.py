"""Writes rendered frames as an animated GIF (Pillow) or, when ffmpeg is on PATH, MP4."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import numpy as np
from PIL import Image

from .errors import COMMAND_LINE, AnimateError


def gif_to(path: Path, pictures: list[np.ndarray], fps: float) -> None:
    """An endlessly looping GIF of `pictures` (RGB arrays), `fps` frames per second."""
    images = [Image.fromarray(p).quantize(colors=128, method=Image.Quantize.MEDIANCUT)
              for p in pictures]
    duration = max(20, round(1000.0 / fps))  # ms; browsers slow anything faster down
    images[0].save(path, format="GIF", save_all=True, append_images=images[1:],
                   duration=duration, loop=0, disposal=1)


def ffmpeg() -> str:
    """The ffmpeg executable, or the user's error when there is none."""
    found = shutil.which("ffmpeg")
    if found is None:
        raise AnimateError(COMMAND_LINE, "--mp4", "ffmpeg is not on PATH; install it or "
                           "leave --mp4 out (the GIF needs nothing more)")
    return found


def mp4_to(path: Path, pictures: list[np.ndarray], fps: float, executable: str) -> None:
    """H.264 MP4 of `pictures` through `executable` (ffmpeg), raw RGB on its stdin."""
    height, width = pictures[0].shape[:2]
    command = [executable, "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24",
               "-s", f"{width}x{height}", "-r", f"{fps:g}", "-i", "-",
               "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p", str(path)]
    done = subprocess.run(command, input=b"".join(p.tobytes() for p in pictures),
                          capture_output=True)
    if done.returncode != 0:
        lines = done.stderr.decode(errors="replace").strip().splitlines()
        why = lines[-1] if lines else f"exit status {done.returncode}"
        raise AnimateError(str(path), "--mp4", f"ffmpeg failed ({why}); leave --mp4 out "
                           "for the GIF alone")
