"""The 3-PSS robot of a co-simulation run drawn moving (``cosim animate RESULT.csv``):
geometry from the Pss3Plant FMU's parameters, motion from the result CSV, frames drawn
with matplotlib (Agg) and written as a GIF with Pillow (MP4 through ffmpeg when present).
See docs/animation.md."""
