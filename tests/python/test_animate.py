"""cosim animate: the drawn robot against the plant FMU's kinematics, the GIF it writes,
the end stops it marks and the user mistakes it refuses.

The independent truth is the Pss3Plant FMU: its leg length parameter `a` and its outputs
l[1..3], which its own (Rust) inverse kinematics computes from its state theta. The
animation draws from theta with its own Python kinematics and parameters read from the
FMU's modelDescription.xml, so a wrong azimuth, sign, rotation order or root shows as a
leg of the wrong length or a slider off the plant's l."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.animate.cli import main  # noqa: E402
from robofmu.animate.draw import GHOST, LEG, Canvas  # noqa: E402
from robofmu.animate.frames import make_frames  # noqa: E402
from robofmu.animate.geometry import pose, robot  # noqa: E402
from robofmu.animate.motion import Motion, read_motion  # noqa: E402
from robofmu.animate.plant import plant_parameters  # noqa: E402
from robofmu.master import Master  # noqa: E402
from robofmu.scenario import load_scenario  # noqa: E402
from conftest import fmu_path  # noqa: E402

PLANT = Path(fmu_path("Pss3Plant"))
SIZE = 100  # px: small pictures keep the test cheap


@pytest.fixture(scope="module")
def runs(tmp_path_factory) -> dict[str, Path]:
    """Result CSVs of two closed-loop runs: the thesis's path 1 (every actuator from
    strokeMin to strokeMax) and a motion that turns about all three axes."""
    folder = tmp_path_factory.mktemp("runs")
    out = {}
    for name in ("path1_cubic", "three_axis_cubic"):
        scenario = load_scenario(ROOT / "scenarios" / f"{name}.toml", ROOT / "dist")
        out[name] = folder / f"{name}.csv"
        Master(scenario).run().write_csv(out[name])
    return out


@pytest.fixture(scope="module")
def rob():
    return robot(plant_parameters(PLANT))


def drawn_legs(canvas: Canvas) -> list[np.ndarray]:
    """The legs as matplotlib holds them after drawing: (2, 3) arrays, slider end first."""
    return [np.array(line.get_data_3d()).T for line in canvas.axes.lines
            if line.get_color() == LEG and line.get_linestyle() == "-"]


@pytest.mark.parametrize("name", ["three_axis_cubic", "path1_cubic"])
def test_drawn_legs_have_the_plants_length_and_sliders_its_l(runs, rob, name):
    motion = read_motion(runs[name])
    a = plant_parameters(PLANT)["a"]
    canvas = Canvas(rob, SIZE, name)
    frames = make_frames(rob, motion, 4)
    assert [f.row for f in frames] == [0, 667, 1333, 2000]  # 2001 rows, evenly spread
    for frame in frames:
        canvas.render(frame)
        legs = drawn_legs(canvas)
        assert len(legs) == 3
        for i, leg in enumerate(legs):
            # The FMU's l output at this row, placed on the actuator axis.
            slider = rob.h[i] + motion.l[frame.row, i] * rob.u[i]
            assert np.abs(leg[0] - slider).max() < 1e-9
            assert abs(np.linalg.norm(leg[1] - leg[0]) - a) < 1e-9
            assert np.abs(leg[1] - frame.pose.platform[i]).max() == 0.0


@pytest.mark.parametrize("degrees", [(10.0, -8.0, 135.0), (-12.0, 6.0, 128.0),
                                     (3.0, 11.0, 150.0), (0.0, 0.0, 122.06793)])
def test_kinematics_equal_the_fmus_at_tilted_poses(rob, degrees):
    # The FMU's initial state theta0 and its l output at t = 0 (the poses tilt more than
    # any scenario; the first puts leg 1 below the stroke, which the IK does not care for).
    from fmpy import simulate_fmu
    theta = np.radians(degrees)
    starts = {f"theta0[{i + 1}]": theta[i] for i in range(3)}
    first = simulate_fmu(str(PLANT), fmi_type="CoSimulation", start_values=starts,
                         stop_time=1e-3, output_interval=1e-3,
                         output=["l[1]", "l[2]", "l[3]"])[0]
    drawn = pose(rob, theta)
    assert np.abs(drawn.l - np.array(list(first)[1:])).max() < 1e-9
    legs = np.linalg.norm(drawn.platform - drawn.sliders, axis=1)
    assert np.abs(legs - rob.leg_length).max() < 1e-9


def test_gif_decodes_with_the_frames_asked_for(runs, tmp_path, capsys):
    out = tmp_path / "out"
    code = main([str(runs["path1_cubic"]), "--out", str(out), "--frames", "7", "--fps", "5",
                 "--size", str(SIZE), "--fmu", str(PLANT)])
    assert code == 0, capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == ["path1_cubic.gif"]
    with Image.open(out / "path1_cubic.gif") as gif:
        assert gif.format == "GIF" and gif.n_frames == 7 and gif.size == (SIZE, SIZE)
        assert gif.info["duration"] == 200  # ms at 5 frames per second
        gif.seek(6)
        last = np.asarray(gif.convert("RGB"))
    assert "leg 3 upper at 2.000 s" in capsys.readouterr().out
    assert red_pixels(last) > 0


def red_pixels(rgb: np.ndarray) -> int:
    r, g, b = (rgb[:, :, k].astype(int) for k in range(3))
    return int(np.count_nonzero((r > 200) & (g < 80) & (b < 80)))


def test_path1_marks_the_stops_it_starts_and_ends_at(runs, rob):
    # Path 1 of the thesis drives all three actuators from strokeMin (2 mm) to strokeMax
    # (152 mm): every leg at its lower stop in the first frame, its upper in the last.
    motion = read_motion(runs["path1_cubic"])
    frames = make_frames(rob, motion, 5)
    assert [list(f.stops) for f in frames] == [[-1] * 3, [0] * 3, [0] * 3, [0] * 3, [1] * 3]
    canvas = Canvas(rob, SIZE, "path1")
    assert red_pixels(canvas.render(frames[0])) > 0
    assert red_pixels(canvas.render(frames[2])) == 0


def test_a_stop_touched_between_frames_shows_in_the_next(rob):
    # A made-up run: leg 2 reaches strokeMax at row 3 only; frames at rows 0, 5 and 10.
    lo, hi = rob.stroke
    l = np.full((11, 3), 0.5 * (lo + hi))
    l[3, 1] = hi
    theta = np.tile(np.radians([0.0, 0.0, 139.79]), (11, 1))
    motion = Motion(source="made-up", plant="plant", time=np.arange(11.0), theta=theta,
                    planned=None, l=l, at_stop=None)
    frames = make_frames(rob, motion, 3)
    assert [f.row for f in frames] == [0, 5, 10]
    assert [list(f.stops) for f in frames] == [[0, 0, 0], [0, 1, 0], [0, 0, 0]]


def test_the_ghost_is_the_platform_at_the_planned_angles(runs, rob):
    motion = read_motion(runs["three_axis_cubic"])
    frame = make_frames(rob, motion, 3)[1]
    canvas = Canvas(rob, SIZE, "ghost")
    canvas.render(frame)
    outline = [np.array(line.get_data_3d()).T for line in canvas.axes.lines
               if line.get_color() == GHOST and len(line.get_xdata()) == 4][0]
    planned = pose(rob, motion.planned[frame.row])
    assert np.abs(outline[:3] - planned.platform).max() < 1e-12
    assert frame.ghost is not None and not np.array_equal(frame.ghost, frame.pose.platform)


def user_error(capsys, argv) -> str:
    assert main(argv) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("cosim: ") and captured.out == ""
    return lines[0]


def test_user_mistakes_get_one_line_and_exit_2(runs, tmp_path, capsys, monkeypatch):
    csv = str(runs["path1_cubic"])
    out = ["--out", str(tmp_path / "out"), "--fmu", str(PLANT)]
    assert "nothing.csv: result CSV: no such file" in user_error(
        capsys, [str(tmp_path / "nothing.csv"), *out])
    bare = tmp_path / "bare.csv"
    bare.write_text('"time","x.y"\n0.0,1.0\n')
    assert "bare.csv: plant.theta[1]: no such columns" in user_error(capsys, [str(bare), *out])
    assert "--frames: 0 frames" in user_error(capsys, [csv, *out, "--frames", "0"])
    assert "need 4.8 GB" in user_error(capsys, [csv, *out, "--frames", "100", "--size", "4000"])
    assert "--param lq=1" in user_error(capsys, [csv, *out, "--param", "lq=1"])
    assert "cannot reach" in user_error(capsys, [csv, *out, "--param", "a=0.3"])
    with warnings.catch_warnings():  # ld = 1e300 overflows: refused with no numpy warning
        warnings.simplefilter("error")
        assert "cannot reach" in user_error(capsys, [csv, *out, "--param", "ld=1e300"])
    assert "Planner.fmu: lp: no such parameter" in user_error(
        capsys, [csv, "--out", str(tmp_path / "out"), "--fmu", fmu_path("Planner")])
    monkeypatch.setenv("PATH", str(tmp_path))
    assert "--mp4: ffmpeg is not on PATH" in user_error(capsys, [csv, *out, "--mp4"])
    assert not (tmp_path / "out").exists()


def test_mp4_pipes_every_frame_to_ffmpeg(runs, tmp_path, capsys, monkeypatch):
    # A stand-in ffmpeg that writes what it was given: the byte count of its stdin and
    # its arguments, into its last argument (the output file).
    fake = tmp_path / "bin" / "ffmpeg"
    fake.parent.mkdir()
    fake.write_text('#!/bin/sh\nfor a; do out=$a; done\n{ wc -c; echo "$@"; } > "$out"\n')
    fake.chmod(0o755)
    monkeypatch.setenv("PATH", f"{fake.parent}:/usr/bin:/bin")
    out = tmp_path / "out"
    assert main([str(runs["path1_cubic"]), "--out", str(out), "--frames", "3", "--size",
                 str(SIZE), "--fmu", str(PLANT), "--mp4"]) == 0, capsys.readouterr().err
    count, arguments = (out / "path1_cubic.mp4").read_text().splitlines()
    assert int(count) == 3 * SIZE * SIZE * 3  # three RGB frames
    assert f"-s {SIZE}x{SIZE} -r 10 -i -" in arguments


def test_without_l_columns_the_stops_come_from_the_kinematics(runs, rob):
    # The same run with the plant's l left out: the flags from the animation's inverse
    # kinematics of theta equal those from the FMU's l.
    import dataclasses
    motion = read_motion(runs["path1_cubic"])
    with_l = [list(f.stops) for f in make_frames(rob, motion, 9)]
    without = [list(f.stops) for f in make_frames(rob, dataclasses.replace(motion, l=None), 9)]
    assert without == with_l and with_l[0] == [-1] * 3 and with_l[-1] == [1] * 3


def test_param_moves_the_end_stop(runs, tmp_path, capsys):
    # strokeMax = 0.1 m: the first frame whose interval reaches l = 0.1 m in the FMU's
    # l output (path 1 moves the three actuators alike) is the first marked.
    motion = read_motion(runs["path1_cubic"])
    frames = make_frames(rob_with(strokeMax=0.1), motion, 11)
    first = next(k for k, row in enumerate(f.row for f in frames) if motion.l[row, 0] >= 0.1)
    expected = f"leg 1 upper at {frames[first].time:.3f} s"
    assert main([str(runs["path1_cubic"]), "--out", str(tmp_path), "--frames", "11",
                 "--size", str(SIZE), "--fmu", str(PLANT), "--param", "strokeMax=0.1"]) == 0
    assert expected in capsys.readouterr().out
    assert all(list(f.stops) == [1] * 3 for f in frames[first:])


def rob_with(**overrides):
    return robot(plant_parameters(PLANT, overrides))
