"""Your own loop with a window on it, as with mujoco.viewer.launch_passive: the UR5e built from
its DH table as your own mujoco.MjModel / MjData sways through a slow joint-space motion under
mjarm's computed-torque controller in a plain mj_step1/mj_step2 loop; mjarm.viewer draws it,
with the tool's reference pose as a marker and the tracking error in the "Your plots" figure.
Double-click a link and Ctrl + right drag it to push the arm.

    python 08_passive_viewer.py        until the window is closed
    python 08_passive_viewer.py 3      three simulated seconds

Needs a display (or xvfb-run). Exits 0 when the loop ran and the window drew it."""
import sys
import time

import mujoco
import numpy as np

import mjarm
import mjarm.viewer

seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 0.0
PI = np.pi
rows = [dict(d=0.1625, alpha=PI / 2), dict(a=-0.425), dict(a=-0.3922),
        dict(d=0.1333, alpha=PI / 2), dict(d=0.0997, alpha=-PI / 2), dict(d=0.0996)]
arm = mjarm.DhArm(name="ur5e_dh", links=[mjarm.DhLink(**row) for row in rows],
                  actuators=mjarm.DhActuators.motor, effort=150.0, damping=0.5)
model = mujoco.MjModel.from_xml_string(mjarm.dh_mjcf(arm))
data = mujoco.MjData(model)
chain = mjarm.Chain(model, "end")
controller = mjarm.ComputedTorqueController(chain)
reference = mjarm.Reference()
home = np.array([0.0, -1.2, 1.4, -1.8, -1.57, 0.0])
amplitude, phase, rate = 0.3, np.array([0, PI / 3, 2 * PI / 3]), 0.8 * np.array([1.0, 1.5, 2.0])


def sway(t):
    """The first three joints sway about home: position, velocity, acceleration at time t."""
    q, qd, qdd = home.copy(), np.zeros(6), np.zeros(6)
    q[:3] += amplitude * np.sin(rate * t + phase)
    qd[:3] = amplitude * rate * np.cos(rate * t + phase)
    qdd[:3] = -amplitude * rate**2 * np.sin(rate * t + phase)
    return q, qd, qdd


data.qpos[:], data.qvel[:], _ = sway(0.0)  # the arm starts on the reference
mujoco.mj_forward(model, data)
command = np.zeros(6)
worst = 0.0
camera = mjarm.CameraSpec.free_camera([0.0, 0.0, 0.4], 2.2, 135.0, -20.0)
with mjarm.viewer.launch_passive(model, data, camera=camera, show_figures=True) as viewer:
    start = time.monotonic()
    while viewer.is_running() and (seconds <= 0 or data.time < seconds):
        reference.joint.q, reference.joint.qd, reference.joint.qdd = sway(data.time)
        mujoco.mj_step1(model, data)
        controller.compute(data, reference, command)
        data.ctrl[:] = command
        mujoco.mj_step2(model, data)

        wanted = mjarm.forward_kinematics(chain, reference.joint.q)
        error = np.linalg.norm(mjarm.forward_kinematics(chain, data.qpos).p - wanted.p)
        worst = max(worst, error)
        viewer.add_frame(wanted, 0.08)
        viewer.add_text(wanted.p + [0, 0, 0.06], "reference")
        viewer.plot("tool error [mm]", 1e3 * error)
        viewer.sync()
        ahead = start + data.time - time.monotonic()  # at the wall clock's pace
        if ahead > 0:
            time.sleep(ahead)
report = viewer.report
print(f"{data.time:.2f} s simulated, {viewer.syncs} states synced, {report.frames} frames drawn, "
      f"worst tool error {worst * 1e3:.2f} mm; the window ended by: {report.ended_by}")
raise SystemExit(0 if viewer.syncs > 0 and report.frames > 0 else 1)
