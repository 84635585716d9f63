"""From a target point to motor torques: IK gives the goal configuration, a quintic in joint
space is the reference, computed torque drives the Panda's motors in a simulation ticked from
Python, and the hand must then hold the target within 1 mm for 200 ms. Exits 0 when it held."""
import numpy as np

import mjarm

robot = mjarm.Robot.bundled("panda_torque")
chain = mjarm.Chain(robot, "attachment_site")
kin = mjarm.ChainKinematics(chain)

sim = mjarm.Simulation(robot, mjarm.SimulationOptions(mjarm.SimulationMode.torque, 0.002))
sim.reset("home")
q0 = chain.gather(sim.qpos)
p_target = kin.update(q0).p + np.array([0.10, -0.15, -0.10])

# target -> joints
ik = mjarm.PositionIk(chain)
solution = ik.solve(p_target, q0)
assert solution.ok(), solution

# joints -> torques, every 2 ms
sim.add_controller(mjarm.ComputedTorqueController(chain))
T = 1.0
trajectory = mjarm.QuinticTrajectory(q0, solution.q, T)
reference = mjarm.Reference()
hold_start, held, worst_in_hold = None, False, 0.0
while sim.time < 3.0 and not held:
    reference.joint.q, reference.joint.qd, reference.joint.qdd = trajectory.at(min(sim.time, T))
    if sim.time >= T:
        reference.joint.qd = np.zeros(chain.size)
        reference.joint.qdd = np.zeros(chain.size)
    tick = sim.tick(reference)
    assert tick.ok(), sim.describe(tick.fault)
    error = np.linalg.norm(kin.update(chain.gather(sim.qpos)).p - p_target)
    if error <= 1e-3:
        hold_start = sim.time if hold_start is None else hold_start
        worst_in_hold = max(worst_in_hold, error)
        held = sim.time - hold_start >= 0.2
    else:
        hold_start, worst_in_hold = None, 0.0

print(f"held within 1 mm for 200 ms: {held} (from t = {hold_start:.3f} s, worst "
      f"{worst_in_hold * 1e3:.3f} mm)" if hold_start is not None else "never within 1 mm")
raise SystemExit(0 if held else 1)
