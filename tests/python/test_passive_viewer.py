"""mjarm.viewer.launch_passive on a loop of the test's own, in an Xvfb of the test's own (started
here, stopped by its PID whatever the outcome): sync from a stepping thread, the user's mujoco
objects, a scripted Ctrl drag that pulls the selected body, markers and plots, closing, and the
errors."""
import math
import os
import shutil
import signal
import subprocess
import threading
import time

import mujoco
import numpy as np
import pytest

import mjarm
import mjarm.viewer

FLOATING_BOX = """
<mujoco model="floating_box">
  <option gravity="0 0 0" timestep="0.002"/>
  <worldbody>
    <light pos="0 -1 2" dir="0 0.5 -1"/>
    <body name="box" pos="0 0 0.5">
      <freejoint/>
      <geom type="box" size="0.08 0.08 0.08" rgba="0.8 0.3 0.2 1" mass="1"/>
    </body>
  </worldbody>
</mujoco>
"""

# looking along +y at the box: image right is world +x
CAMERA = mjarm.CameraSpec.free_camera([0.0, 0.0, 0.5], 1.2, 90.0, 0.0)


@pytest.fixture(scope="module")
def display():
    """An X server of this test's own: it picks a free display and reports it (-displayfd)."""
    xvfb = shutil.which("Xvfb")
    assert xvfb, "no Xvfb on PATH: scripts/setup.sh installs Debian's xvfb"
    read, write = os.pipe()
    server = subprocess.Popen(
        [xvfb, "-displayfd", str(write), "-screen", "0", "1280x1024x24", "-nolisten", "tcp"],
        pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        start_new_session=True)
    os.close(write)
    try:
        number = b""
        deadline = time.monotonic() + 60
        while not number.endswith(b"\n") and time.monotonic() < deadline:
            chunk = os.read(read, 16)
            if not chunk:
                break
            number += chunk
        assert number.endswith(b"\n"), "Xvfb reported no display"
        previous = os.environ.get("DISPLAY")
        os.environ["DISPLAY"] = ":" + number.decode().strip()
        yield os.environ["DISPLAY"]
        if previous is None:
            del os.environ["DISPLAY"]
        else:
            os.environ["DISPLAY"] = previous
    finally:
        os.close(read)
        os.kill(server.pid, signal.SIGTERM)
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.kill(server.pid, signal.SIGKILL)
            server.wait()


def step_and_sync(viewer, model, data, each=None, limit=120.0):
    """The user's loop on the wall clock, until the window closes (bounded)."""
    start = time.monotonic()
    k = 0
    while viewer.is_running():
        mujoco.mj_step(model, data)
        if each:
            each()
        viewer.sync()
        k += 1
        ahead = start + k * model.opt.timestep - time.monotonic()
        if ahead > 0:
            time.sleep(ahead)
        assert time.monotonic() - start < limit, "the script did not end the window"


def test_a_scripted_ctrl_drag_pulls_the_selected_body_of_the_users_mujoco_data(display):
    model = mujoco.MjModel.from_xml_string(FLOATING_BOX)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    script = "wait 10\nselect 0 0\nwait 5\npress ctrl+right 0 0\nmove 120 0\nwait 40\nrelease\n" \
             "wait 5\n"
    largest = [0.0]

    def watch():
        largest[0] = max(largest[0], data.xfrc_applied[1, 0])

    with mjarm.viewer.launch_passive(model, data, camera=CAMERA, script=script, width=640,
                                     height=480) as viewer:
        step_and_sync(viewer, model, data, watch)
        assert viewer.selected_body == 1
    assert viewer.report.ended_by == "end of script"
    assert largest[0] > 0.0, "the spring pulled along image right, world +x"
    assert data.qpos[0] > 0.02
    assert np.all(data.xfrc_applied[1] == 0.0), "the spring ends with the drag"


def test_sync_from_a_stepping_thread_and_close_from_the_main_one(display):
    model = mujoco.MjModel.from_xml_string(FLOATING_BOX)
    data = mujoco.MjData(model)
    data.qvel[3:6] = [0.0, 0.0, 1.0]  # spinning
    with mjarm.viewer.launch_passive(model, data, width=640, height=480,
                                     show_figures=True) as viewer:
        done = threading.Event()

        def loop():
            while viewer.is_running() and not done.is_set():
                mujoco.mj_step(model, data)
                viewer.add_frame(np.eye(4))
                viewer.add_sphere([0.0, -0.2, 0.5], 0.03, [0.1, 0.9, 0.1, 1.0])
                viewer.add_text([0.0, -0.2, 0.6], "target")
                viewer.plot("sine", math.sin(data.time))
                viewer.sync()
                time.sleep(0.001)

        worker = threading.Thread(target=loop)
        worker.start()
        deadline = time.monotonic() + 60
        while viewer.syncs < 200 and time.monotonic() < deadline:
            time.sleep(0.01)
        viewer.close()
        done.set()
        worker.join(timeout=60)
        assert not worker.is_alive()
    assert viewer.syncs >= 200
    assert not viewer.is_running()
    assert viewer.report.ended_by == "closed by the program"
    assert viewer.report.frames > 0


def test_a_simulation_is_shown_with_its_own_robot_and_data(display):
    sim = mjarm.Simulation(mjarm.Robot.bundled("panda"))
    with mjarm.viewer.launch_passive(sim, width=640, height=480) as viewer:
        viewer.sync()
        assert viewer.is_running()
    assert viewer.syncs == 1
    with pytest.raises(TypeError, match="no data"):
        mjarm.viewer.launch_passive(sim, sim.data)


def test_screenshots_of_a_script_are_listed(display, tmp_path):
    model = mujoco.MjModel.from_xml_string(FLOATING_BOX)
    data = mujoco.MjData(model)
    shot = tmp_path / "shot.png"
    viewer = mjarm.viewer.launch_passive(model, data, camera=CAMERA,
                                         script=f"wait 5\nscreenshot {shot}\n")
    step_and_sync(viewer, model, data)
    viewer.close()
    assert viewer.report.screenshots == [str(shot)]
    assert shot.stat().st_size > 1000


def test_bad_input_is_refused_with_a_clear_error(display):
    model = mujoco.MjModel.from_xml_string(FLOATING_BOX)
    other = mujoco.MjModel.from_xml_string("<mujoco><worldbody><body><freejoint/>"
                                           "<geom size='0.1'/></body></worldbody></mujoco>")
    with pytest.raises(mjarm.Error, match="another model|made for"):
        mjarm.viewer.launch_passive(model, mujoco.MjData(other))
    with pytest.raises(mjarm.Error, match="render_hz"):
        mjarm.viewer.launch_passive(model, mujoco.MjData(model), render_hz=0.0)
    with pytest.raises(mjarm.Error, match="unknown command"):
        mjarm.viewer.launch_passive(model, mujoco.MjData(model), script="jump 3\n")
    with pytest.raises(TypeError, match="data"):
        mjarm.viewer.launch_passive(model)
    viewer = mjarm.viewer.launch_passive(model, mujoco.MjData(model))
    with pytest.raises(mjarm.Error, match="non-finite"):
        viewer.plot("error", float("nan"))
    viewer.close()


def test_no_display_is_a_clear_error(monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    model = mujoco.MjModel.from_xml_string(FLOATING_BOX)
    with pytest.raises(mjarm.Error, match="no display"):
        mjarm.viewer.launch_passive(model, mujoco.MjData(model))
