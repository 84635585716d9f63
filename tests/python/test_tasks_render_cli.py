"""The shelf pick from Python, the renderer (images as NumPy arrays), python3 -m mjarm, and the
examples under examples/python (each run to completion)."""
import glob
import json
import os
import runpy
import subprocess
import sys

import numpy as np
import pytest

import mjarm


def test_shelf_pick_holds_1mm(tmp_path):
    options = mjarm.ShelfPickOptions()
    options.request.robot = "planar2"
    options.request.controller = "osc"
    options.request.seed = 3
    options.record = str(tmp_path / "pick")
    report = mjarm.run_shelf_pick(options)
    assert report.ok() and report.outcome == mjarm.PickOutcome.held
    assert report.metrics.held and report.metrics.hold_max <= 1e-3
    assert os.path.exists(os.path.join(options.record, "summary.json"))
    again = mjarm.run_shelf_pick(options)
    assert again.metrics.time_to_tolerance == report.metrics.time_to_tolerance
    bad = mjarm.ShelfPickOptions()
    bad.request.controller = "nope"
    with pytest.raises(mjarm.Error, match="nope"):
        mjarm.run_shelf_pick(bad)


def test_render_image_is_numpy(panda):
    os.environ.setdefault("EGL_PLATFORM", "surfaceless")
    data = panda.make_data()
    data.qpos[:] = panda.keyframe_qpos("home")
    data.forward()
    renderer = mjarm.OffscreenRenderer(panda, 64, 48)
    image = renderer.render(data, mjarm.frame_robot(panda, data))
    assert image.shape == (48, 64, 3) and image.dtype == np.uint8
    assert image.std() > 1.0  # not a blank picture
    renderer.close()


def test_python_m_mjarm_forwards_to_the_cli():
    out = subprocess.run([sys.executable, "-m", "mjarm", "--version"], capture_output=True, text=True)
    assert out.returncode == 0 and "0.1.0" in out.stdout
    out = subprocess.run([sys.executable, "-m", "mjarm", "no-such-command"], capture_output=True, text=True)
    assert out.returncode == 2


EXAMPLES = sorted(glob.glob(os.path.join(
    os.environ.get("MJARM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")),
    "examples", "python", "*.py")))


@pytest.mark.parametrize("path", EXAMPLES, ids=[os.path.basename(p) for p in EXAMPLES])
def test_example_runs(path, monkeypatch, capsys):
    if "viewer" in os.path.basename(path):
        # a window: on a display of its own, for one simulated second (at the wall clock's pace)
        command = ["bash", os.path.join(os.path.dirname(__file__), "..", "setup", "with_display.sh"),
                   sys.executable, path, "1"]
        out = subprocess.run(command, capture_output=True, text=True, timeout=600)
        assert out.returncode == 0, out.stdout + out.stderr
        return
    # run as `python path` runs it, in this process: another interpreter would only add its start
    # (NumPy, mujoco and the sanitized extension loaded again, most of a short example's CPU)
    monkeypatch.setattr(sys, "argv", [path])
    monkeypatch.syspath_prepend(os.path.dirname(path))
    try:
        runpy.run_path(path, run_name="__main__")
    except SystemExit as end:
        assert end.code in (0, None), f"exit {end.code}\n" + "".join(capsys.readouterr())


def test_examples_exist():
    names = [os.path.basename(p) for p in EXAMPLES]
    assert any("ik" in n for n in names) and any("clik" in n for n in names)
    assert any("torque" in n for n in names) and any("pick_and_place" in n for n in names)


def test_video_from_rendered_frames(panda, tmp_path):
    os.environ.setdefault("EGL_PLATFORM", "surfaceless")
    data = panda.make_data()
    renderer = mjarm.OffscreenRenderer(panda, 64, 48)
    camera = mjarm.frame_robot(panda, data)
    path = tmp_path / "clip.mp4"
    video = mjarm.VideoWriter(str(path), 64, 48, 25.0)
    home = panda.keyframe_qpos("home")
    for k in range(5):
        data.qpos[:] = home * (k / 4.0)
        data.forward()
        video.write(renderer.render(data, camera))
    with pytest.raises(ValueError, match=r"frame: expected a uint8 array of shape \(48, 64, 3\)"):
        video.write(np.zeros((10, 10, 3), dtype=np.uint8))
    video.close()
    assert video.frames == 5 and video.complete
    assert path.stat().st_size > 0


def test_binding_benchmark_runs_and_reports_both_controller_forms():
    out = subprocess.run([sys.executable, "-m", "mjarm.bench", "--rounds", "1", "--calls", "100",
                          "--ticks", "100", "--clock", "cpu", "--json"],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    figures = json.loads(out.stdout)
    for key in ("fk_us", "ik_us", "controller_us", "controller_out_us", "tick_rtf"):
        assert figures["python"][key] > 0, key
    assert figures["clock"] == "cpu" and len(figures["load_average"]) == 2

def test_binding_benchmark_refuses_a_bad_repeat(capsys):
    import mjarm.bench
    with pytest.raises(SystemExit) as bad:
        mjarm.bench.main(["--repeat", "0"])
    assert bad.value.code == 2 and "--repeat must be in 1..50" in capsys.readouterr().err
