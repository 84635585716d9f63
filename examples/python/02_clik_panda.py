"""Closed-loop inverse kinematics (CLIK) on the Panda, written in Python the way the tutorials
write it, on mjarm's kinematics: every step takes the body log error e = log(X_WE^-1 X_WT), the
local Jacobian J_E and dexp^-1(e), and moves q by a damped least-squares step. Exits 0 when the
hand reaches the target pose within 1e-6 m and 1e-6 rad inside the joint limits."""
import numpy as np

import mjarm

robot = mjarm.Robot.bundled("panda")
chain = mjarm.Chain(robot, "attachment_site")
kin = mjarm.ChainKinematics(chain)

q = chain.gather(robot.keyframe_qpos("home"))
X_WT = mjarm.Pose.from_rpy([0.45, 0.10, 0.40], [np.pi, 0.0, 0.5236])

gain, damping = 0.5, 1e-3
for step in range(300):
    X_WE = kin.update(q)
    e = mjarm.log_error(X_WE, X_WT)  # [v; w] in E
    if np.linalg.norm(e[:3]) < 1e-7 and np.linalg.norm(e[3:]) < 1e-7:
        break
    J = mjarm.log_error_jacobian(e) @ kin.jacobian(mjarm.JacobianFrame.local)
    dq = J.T @ np.linalg.solve(J @ J.T + damping**2 * np.eye(6), gain * e)
    q = chain.clamp(q + dq)

pos, ang = mjarm.frame_errors(kin.update(q), X_WT)
print(f"CLIK: {step} steps, position error {pos:.2e} m, orientation error {ang:.2e} rad")
print("q =", np.round(q, 4))
ok = pos < 1e-6 and ang < 1e-6 and chain.within_limits(q)
print("ok" if ok else "FAILED")
raise SystemExit(0 if ok else 1)
