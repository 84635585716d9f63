"""Position IK with a pull to the middle of each joint range (the classic damped-least-squares
tutorial loop, as one library call): reach three points with the Panda's hand, print the
iterations, and check each answer with an independent forward kinematics and the joint limits.
Exits 0 when every point was reached within 0.1 mm inside the limits."""
import numpy as np

import mjarm

robot = mjarm.Robot.bundled("panda")
chain = mjarm.Chain(robot, "attachment_site")

options = mjarm.PositionIkOptions()
options.limits = mjarm.LimitBias(centre_gain=0.05, repulsion_gain=0.2, repulsion_zone=0.15)
options.tolerance = 1e-4  # m
trace = []
options.on_iteration = lambda it, pe, oe, q: trace.append(pe)
ik = mjarm.PositionIk(chain, options)

seed = chain.gather(robot.keyframe_qpos("home"))
ok = True
for target in ([0.5, 0.0, 0.4], [0.3, 0.3, 0.6], [0.4, -0.2, 0.2]):
    trace.clear()
    result = ik.solve(np.array(target), seed)
    reached = mjarm.forward_kinematics(chain, result.q).p
    error = np.linalg.norm(reached - target)
    print(f"target {target}: {result.status.name} after {result.iterations} iterations, "
          f"error {error * 1e3:.3f} mm, first errors {np.round(trace[:3], 4)}")
    # the centre pull keeps the joints away from their limits
    margin = np.min(np.minimum(result.q - chain.lower, chain.upper - result.q))
    print(f"  closest joint to a limit: {margin:.3f} rad")
    ok = ok and result.ok() and error <= 1e-4 and chain.within_limits(result.q)
print("ok" if ok else "FAILED")
raise SystemExit(0 if ok else 1)
