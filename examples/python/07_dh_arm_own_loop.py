"""Your own loop on an arm built from code: the UR5e from its published DH table (standard
convention) as the user's own mujoco.MjModel / MjData, IK started from where the arm is, a
computed-torque controller in a plain mj_step1/mj_step2 loop, the state read by name, and a
snapshot restored to replay the last second bit for bit.
Exits 0 when the tool reached the target within 1 mm and the replay matched."""
import mujoco
import numpy as np

import mjarm

PI = np.pi
rows = [dict(d=0.1625, alpha=PI / 2), dict(a=-0.425), dict(a=-0.3922),
        dict(d=0.1333, alpha=PI / 2), dict(d=0.0997, alpha=-PI / 2), dict(d=0.0996)]
arm = mjarm.DhArm(name="ur5e_dh", links=[mjarm.DhLink(**row) for row in rows],
                  actuators=mjarm.DhActuators.motor, effort=150.0, damping=0.5)
model = mujoco.MjModel.from_xml_string(mjarm.dh_mjcf(arm))
data = mujoco.MjData(model)
state = mjarm.Data(data)             # the same memory, by name
named = state.named

for joint, value in zip(named.qpos.names, [0.0, -PI / 2, PI / 2, -PI / 2, -PI / 2, 0.0]):
    named.qpos[joint] = value
mujoco.mj_forward(model, data)
print(f"{model.nbody - 1} links; the tool at {np.round(named.site_xpos['end'], 4)} m")

chain = mjarm.Chain(model, "end")
goal = mjarm.forward_kinematics(chain, np.array([0.5, -1.2, 1.4, -1.8, -1.57, 0.3]))
solution = mjarm.PoseIk(chain).solve(goal, data)   # from the arm's current joints
print(f"IK: {solution.status.name} after {solution.iterations} iterations")

controller = mjarm.ComputedTorqueController(chain)
reference = mjarm.Reference()
reference.joint.q, reference.joint.qd, reference.joint.qdd = solution.q, np.zeros(6), np.zeros(6)
command = np.zeros(6)


def run(seconds):
    for _ in range(round(seconds / model.opt.timestep)):
        mujoco.mj_step1(model, data)
        controller.compute(data, reference, command)
        data.ctrl[:] = command
        mujoco.mj_step2(model, data)


run(2.0)
snapshot = state.snapshot()
run(1.0)
after = data.qpos.copy()
state.restore(snapshot)
run(1.0)
replayed = np.array_equal(after, data.qpos)
mujoco.mj_forward(model, data)
error = np.linalg.norm(named.site_xpos["end"] - goal.p)
print(f"tool error {error * 1e3:.3f} mm; joint 2 torque {named.actuator_force['joint2'][0]:.2f} N m; "
      f"replay from the snapshot {'bit for bit' if replayed else 'DIFFERENT'}")
raise SystemExit(0 if solution.ok() and error < 1e-3 and replayed else 1)
