#!/usr/bin/env python3
"""mink and mjarm's DiffIk side by side: differential IK, iterated to the same random targets.

Both solve the same QP each step (docs/ik.md, "Differential IK"): one pose task on the arm's
frame (body log error, weights 1 on position and orientation, gain 1: the whole error removed in
one step when no limit binds), damping λ‖Δq‖² with the same λ (mink's `damping` and
DiffIkOptions.damping are on the same scale), the joint limits after integration
(mink ConfigurationLimit with gain 1, the exact bound DiffIk uses) and a joint speed limit
(mink VelocityLimit, DiffIkOptions.velocity_limit). mjarm loads the bundled MJCF, mink the same
file through MuJoCo's Python package; mink solves with DAQP.

From the arm's home keyframe, each target is the pose of the frame at a random configuration
within the limits (reachable). A solve steps until the pose error, measured the same way for both
(mjarm's forward kinematics of the step's q, body log error), is within the tolerances, or until
--max-iterations. The first step's velocities are compared (the same QP: they should agree).
Timing is from Python on both sides (mink is a Python library over MuJoCo's bindings and a QP
solver; DiffIk.step is one binding call): the steps of a solve are timed back to back in a second,
identical run without the checks.
"""
import os
import sys

import mink
import mujoco
import numpy as np

import mjarm

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

ROBOTS = ("panda", "iiwa14", "ur5e")
FRAME = "attachment_site"


class MjarmIk:
    name = "mjarm"

    def __init__(self, chain, dt, damping, vmax):
        self.chain, self.dt, self.damping, self.vmax = chain, dt, damping, vmax

    def start(self, q0, X_WT):
        options = mjarm.DiffIkOptions()
        options.dt, options.damping = self.dt, self.damping
        options.velocity_limit = np.full(self.chain.size, self.vmax)
        self.ik = mjarm.DiffIk(self.chain, options)  # fresh: no warm start from another solve
        self.task = self.ik.add_pose_task(frame="", position_weight=1.0, orientation_weight=1.0,
                                          gain=1.0)
        self.ik.set_target(self.task, X_WT)
        self.q = np.array(q0)

    def step(self):
        s = self.ik.step(self.q)
        self.q = s.q_next
        return s.v


class MinkIk:
    name = "mink"

    def __init__(self, model, joints, dt, damping, vmax):
        self.model, self.dt, self.damping = model, dt, damping
        self.limits = [mink.ConfigurationLimit(model, gain=1.0),
                       mink.VelocityLimit(model, {j: vmax for j in joints})]

    def start(self, q0, X_WT):
        self.configuration = mink.Configuration(self.model, np.array(q0))
        self.task = mink.FrameTask(FRAME, "site", position_cost=1.0, orientation_cost=1.0,
                                   gain=1.0)
        self.task.set_target(mink.SE3.from_rotation_and_translation(
            mink.SO3.from_matrix(X_WT.R), X_WT.p))

    @property
    def q(self):
        return self.configuration.q

    def step(self):
        v = mink.solve_ik(self.configuration, [self.task], self.dt, "daqp", self.damping,
                          limits=self.limits)
        self.configuration.integrate_inplace(v, self.dt)
        return v


def solve(side, kin, q0, X_WT, tolerances, max_iterations):
    """Steps to the target; returns (iterations or None, first step's velocity)."""
    side.start(q0, X_WT)
    first = None
    for k in range(max_iterations + 1):
        e = mjarm.log_error(kin.update(side.q), X_WT)
        if np.linalg.norm(e[:3]) <= tolerances[0] and np.linalg.norm(e[3:]) <= tolerances[1]:
            return k, first
        if k == max_iterations:
            return None, first
        v = side.step()
        if first is None:
            first = np.array(v)


def timed(side, q0, X_WT, steps, clock):
    side.start(q0, X_WT)
    begin = clock()
    for _ in range(steps):
        side.step()
    return clock() - begin


def run_robot(name, args, rng, clock, progress, done):
    robot = mjarm.Robot.bundled(name)
    chain = mjarm.Chain(robot, FRAME)
    kin = mjarm.ChainKinematics(chain)
    model = mujoco.MjModel.from_xml_path(os.path.join(mjarm.Robot.models_dir(), f"{name}.xml"))
    if model.nq != chain.size:
        raise SystemExit(f"mink_side_by_side: {name}: expected an arm alone in its model")
    q0 = robot.keyframe_qpos("home")
    sides = [MjarmIk(chain, args.dt, args.damping, args.velocity_limit),
             MinkIk(model, chain.joint_names, args.dt, args.damping, args.velocity_limit)]
    out = {s.name: {"converged": 0, "iterations": [], "steps": 0, "time_ns": 0,
                    "solve_ns": []} for s in sides}
    first_step = 0.0
    equal_iterations = both = 0
    for t in range(args.targets):
        X_WT = kin.update(rng.uniform(chain.lower, chain.upper)).copy()
        result = {}
        for side in sides:
            iterations, first = solve(side, kin, q0, X_WT, (args.position_tolerance,
                                                            args.orientation_tolerance),
                                      args.max_iterations)
            steps = args.max_iterations if iterations is None else iterations
            elapsed = timed(side, q0, X_WT, steps, clock)
            o = out[side.name]
            o["steps"] += steps
            o["time_ns"] += elapsed
            if iterations is not None:
                o["converged"] += 1
                o["iterations"].append(iterations)
                o["solve_ns"].append(elapsed)
            result[side.name] = (iterations, first)
        (im, vm), (ik, vk) = result["mjarm"], result["mink"]
        if vm is not None and vk is not None:
            first_step = max(first_step, float(np.abs(vm - vk).max()))
        if im is not None and ik is not None:
            both += 1
            equal_iterations += im == ik
        progress.update(done + t + 1)
    summary = {"targets": args.targets, "both_converged": both, "equal_iterations": equal_iterations,
               "first_step_velocity_difference": first_step}
    for side, o in out.items():
        it = np.array(o["iterations"]) if o["iterations"] else np.array([np.nan])
        summary[side] = {
            "converged": o["converged"], "mean_iterations": float(np.mean(it)),
            "median_iterations": float(np.median(it)), "max_iterations": float(np.max(it)),
            "step_us": o["time_ns"] / max(1, o["steps"]) * 1e-3,
            "solve_ms": float(np.mean(o["solve_ns"]) * 1e-6) if o["solve_ns"] else float("nan")}
    summary["step_ratio"] = summary["mjarm"]["step_us"] / summary["mink"]["step_us"]
    return summary


def main():
    p = common.parser(__doc__)
    p.add_argument("--robots", default=",".join(ROBOTS),
                   help=f"bundled arms, comma-separated (default {','.join(ROBOTS)})")
    p.add_argument("--targets", type=common.positive(int), default=200,
                   help="random targets per robot (default 200)")
    p.add_argument("--dt", type=common.positive(float), default=0.01, help="step [s] (default 0.01)")
    p.add_argument("--velocity-limit", type=common.positive(float), default=2.0,
                   help="joint speed limit [rad/s] (default 2)")
    p.add_argument("--damping", type=common.positive(float), default=1e-6,
                   help="λ of λ‖Δq‖² (default 1e-6, DiffIk's)")
    p.add_argument("--position-tolerance", type=common.positive(float), default=1e-4,
                   help="converged below this position error [m] (default 1e-4)")
    p.add_argument("--orientation-tolerance", type=common.positive(float), default=1e-3,
                   help="and below this orientation error [rad] (default 1e-3)")
    p.add_argument("--max-iterations", type=common.positive(int), default=500,
                   help="steps before a solve counts as failed (default 500)")
    args = p.parse_args()
    names = [n for n in args.robots.split(",") if n]
    for n in names:
        if n not in mjarm.Robot.bundled_names():
            p.error(f"--robots: '{n}' is not a bundled model")
    clock = common.CLOCKS[args.clock]
    rng = np.random.default_rng(args.seed)
    report = {
        "peer": "mink", "versions": common.versions("mink", "daqp"), "machine": common.machine(),
        "protocol": [
            f"robots {', '.join(names)}, frame {FRAME}, from the keyframe 'home'; {args.targets} "
            f"targets per robot: the frame's pose at q uniform within the limits, numpy "
            f"default_rng({args.seed})",
            f"one pose task (weights 1, gain 1), damping {args.damping}, dt {args.dt} s, joint "
            f"limits after integration (mink ConfigurationLimit gain 1), joint speed ≤ "
            f"{args.velocity_limit} rad/s; mink solves with DAQP",
            f"converged: position error ≤ {args.position_tolerance} m and orientation error ≤ "
            f"{args.orientation_tolerance} rad (body log error of mjarm's FK, the same for both) "
            f"within {args.max_iterations} steps",
            f"time from Python, {args.clock} clock: the steps of each solve timed back to back in "
            "a second identical run (fresh solver, no checks); per step over every step, per "
            "solve over the converged ones",
        ],
        "robots": {},
    }
    progress = common.Progress("targets", args.targets * len(names))
    for k, name in enumerate(names):
        report["robots"][name] = run_robot(name, args, rng, clock, progress, k * args.targets)
    progress.close()
    report["machine"]["load_average_after"] = common.machine()["load_average"]
    common.emit(args, report, format_text(report))


def format_text(report):
    parts = [common.header("mink and mjarm's differential IK side by side", report), ""]
    rows = []
    for name, r in report["robots"].items():
        for side, label in (("mjarm", "mjarm"), ("mink", "mink")):
            s = r[side]
            rows.append([name, label, f"{s['converged']}/{r['targets']}",
                         f"{s['mean_iterations']:.1f}", f"{s['median_iterations']:.0f}",
                         f"{s['max_iterations']:.0f}", f"{s['step_us']:.1f}",
                         f"{s['solve_ms']:.3f}"])
    parts.append(common.table(["robot", "library", "converged", "mean iterations",
                               "median", "max", "per step [µs]", "per solve [ms]"], rows))
    parts += ["", "Both converged / same iteration count / largest first-step velocity "
              "difference [rad/s] / mjarm ÷ mink per step:", ""]
    parts.append(common.table(["robot", "both converged", "same iterations",
                               "first step |Δv|", "mjarm / mink per step"],
                              [[n, r["both_converged"], r["equal_iterations"],
                                f"{r['first_step_velocity_difference']:.1e}",
                                f"{r['step_ratio']:.3f}"] for n, r in report["robots"].items()]))
    return "\n".join(parts)


if __name__ == "__main__":
    main()
