#!/usr/bin/env python3
"""Pinocchio and mjarm side by side on the bundled arms: forward kinematics, the frame Jacobian,
inverse dynamics (RNEA) and the joint-space inertia (CRBA), at the same random configurations.

Both libraries load the same MJCF file: mjarm the bundled model, Pinocchio the same file through
pin.buildModelFromMJCF (its includes inlined first: the parser does not follow them). Agreement is
checked here, from Python, on every configuration: the frame's pose, the Jacobian (Pinocchio's
LOCAL_WORLD_ALIGNED against mjarm's world_aligned, both linear rows first), τ = RNEA(q, v, a)
against mjarm's M·q̈ + h and M = CRBA(q) against mjarm's mass matrix — with armature, which both
put on M's diagonal (0.05–0.2 kg·m² here: a model without it would miss by that much). Timing is
done in C++ on both sides (bench/peers/pinocchio_bench.cpp, built by `make bench-peers`): one call
costs a few hundred ns, less than a Python call's overhead, so only C++ compares the libraries.
That program rebuilds the very model Pinocchio parsed here, checks the agreement again, and times
each call per configuration with Google Benchmark, repetitions randomly interleaved.
"""
import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin

import mjarm

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

ROBOTS = ("panda", "iiwa14", "ur5e")
FRAME = "attachment_site"
TOLERANCE = 1e-10
CALLS = (("fk", "forward kinematics (frame pose)"),
         ("fk_jacobian", "pose + world-aligned frame Jacobian"),
         ("rnea", "inverse dynamics τ(q, v, a) (RNEA)"),
         ("crba", "joint-space inertia M(q) (CRBA)"))


def stage_mjcf(path):
    """The MJCF text of `path` as one file, for Pinocchio's parser: includes inlined, repeated
    top-level sections merged into the first (MuJoCo merges them; the parser reads only the first
    <worldbody>), and <default> moved before the bodies that use its classes (the parser reads in
    document order)."""
    root = ET.parse(path).getroot()
    base = os.path.dirname(path)

    def inline(element):
        for child in list(element):
            if child.tag == "include":
                included = ET.parse(os.path.join(base, child.get("file"))).getroot()
                at = list(element).index(child)
                element.remove(child)
                for k, part in enumerate(included):
                    element.insert(at + k, part)
        for child in element:
            inline(child)

    inline(root)
    first = {}
    for child in list(root):
        if child.tag in first:
            first[child.tag].extend(list(child))
            root.remove(child)
        else:
            first[child.tag] = child
    order = ["compiler", "option", "size", "default"]
    children = sorted(root, key=lambda c: order.index(c.tag) if c.tag in order else len(order))
    for child in list(root):
        root.remove(child)
    root.extend(children)
    return ET.tostring(root, encoding="unicode")


def pinocchio_model(name, directory):
    staged = os.path.join(directory, f"{name}.xml")
    with open(staged, "w") as f:
        f.write(stage_mjcf(os.path.join(mjarm.Robot.models_dir(), f"{name}.xml")))
    return pin.buildModelFromMJCF(staged)


def placement(se3):
    return {"R": se3.rotation.ravel().tolist(), "p": se3.translation.tolist()}


def export(model, name):
    """The model as pinocchio_bench.cpp rebuilds it: joint by joint (the bodies fixed to a joint
    are one inertia in Pinocchio), the frame, gravity."""
    joints = []
    for j in range(1, model.njoints):
        joint = model.joints[j]
        inertia = model.inertias[j]
        entry = {"name": model.names[j], "parent": int(model.parents[j]),
                 "type": joint.shortname(), **placement(model.jointPlacements[j]),
                 "mass": inertia.mass, "lever": inertia.lever.tolist(),
                 "inertia": inertia.inertia.ravel().tolist(),
                 "armature": float(model.armature[joint.idx_v])}
        if entry["type"] == "JointModelRevoluteUnaligned":
            entry["axis"] = joint.extract().axis.tolist()
        joints.append(entry)
    frame = model.frames[model.getFrameId(FRAME)]
    return {"name": name, "frame": FRAME, "gravity": model.gravity.linear.tolist(),
            "joints": joints, "frame_joint": int(frame.parentJoint),
            "frame_placement": placement(frame.placement)}


def configurations(chain, count, rng):
    """q uniform within the joint limits, q̇ uniform in ±2 rad/s, q̈ uniform in ±10 rad/s²."""
    n = chain.size
    q = rng.uniform(chain.lower, chain.upper, size=(count, n))
    return q, rng.uniform(-2.0, 2.0, size=(count, n)), rng.uniform(-10.0, 10.0, size=(count, n))


def agreement(name, model, qs, vs, accs):
    """Largest absolute differences over the configurations, and the largest magnitudes."""
    robot = mjarm.Robot.bundled(name)
    chain = mjarm.Chain(robot, FRAME)
    kin, dyn, data = mjarm.ChainKinematics(chain), mjarm.ChainDynamics(chain), robot.make_data()
    pdata = model.createData()
    frame = model.getFrameId(FRAME)
    worst = dict.fromkeys(("pose", "jacobian", "rnea", "crba"), 0.0)
    size = dict.fromkeys(("tau", "M"), 0.0)
    progress = common.Progress(f"agreement, {name}", len(qs))
    for i, (q, v, a) in enumerate(zip(qs, vs, accs)):
        X = kin.update(q)
        J = kin.jacobian(mjarm.JacobianFrame.world_aligned)
        data.qpos[chain.qpos_addresses] = q
        data.qvel[chain.dof_addresses] = v
        data.forward()
        dyn.update(data)
        tau = dyn.inverse_dynamics(data, a)
        M = dyn.mass_matrix
        pin.forwardKinematics(model, pdata, q)
        pX = pin.updateFramePlacement(model, pdata, frame)
        pJ = pin.computeFrameJacobian(model, pdata, q, frame, pin.LOCAL_WORLD_ALIGNED)
        ptau = pin.rnea(model, pdata, q, v, a)
        pM = pin.crba(model, pdata, q)
        pM = np.triu(pM) + np.triu(pM, 1).T  # crba fills the upper triangle
        worst["pose"] = max(worst["pose"], np.abs(X.p - pX.translation).max(),
                            np.abs(X.R - pX.rotation).max())
        worst["jacobian"] = max(worst["jacobian"], np.abs(J - pJ).max())
        worst["rnea"] = max(worst["rnea"], np.abs(tau - ptau).max())
        worst["crba"] = max(worst["crba"], np.abs(M - pM).max())
        size["tau"] = max(size["tau"], np.abs(ptau).max())
        size["M"] = max(size["M"], np.abs(pM).max())
        progress.update(i + 1)
    progress.close()
    armature = [float(x) for x in model.armature]
    return {"configurations": len(qs), **worst, "largest_tau": size["tau"], "largest_M": size["M"],
            "armature": armature,
            "within_tolerance": bool(max(worst.values()) <= TOLERANCE)}


def run_timing(args, robots, directory):
    path = os.path.join(directory, "input.json")
    with open(path, "w") as f:
        json.dump({"robots": robots}, f)
    out = os.path.join(directory, "timing.json")
    command = [args.bench, f"--input={path}", f"--tolerance={TOLERANCE}",
               f"--benchmark_min_time={args.min_time}",
               f"--benchmark_repetitions={args.repetitions}",
               "--benchmark_enable_random_interleaving=true",
               "--benchmark_report_aggregates_only=true",
               f"--benchmark_out={out}", "--benchmark_out_format=json"]
    # Google Benchmark's console lines are the progress: shown on a terminal only
    console = sys.stderr if sys.stderr.isatty() else subprocess.DEVNULL
    done = subprocess.run(command, stdout=console, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"pinocchio_side_by_side: {args.bench} failed ({done.returncode}): "
                 f"{done.stderr.strip()}")
    with open(out) as f:
        return json.load(f)


def main():
    p = common.parser(__doc__)
    p.add_argument("--robots", default=",".join(ROBOTS),
                   help=f"bundled arms, comma-separated (default {','.join(ROBOTS)})")
    p.add_argument("--configurations", type=common.positive(int), default=1000,
                   help="random configurations, each checked and timed (default 1000)")
    p.add_argument("--bench", default="build-peers/bench_peers_pinocchio",
                   help="the C++ timing program (default build-peers/bench_peers_pinocchio)")
    p.add_argument("--min-time", type=common.positive(float), default=0.2,
                   help="seconds per repetition of each timed call (default 0.2)")
    p.add_argument("--repetitions", type=common.positive(int), default=5,
                   help="repetitions of each timed call, randomly interleaved; the median is "
                        "reported (default 5)")
    p.add_argument("--no-timing", action="store_true",
                   help="check the agreement only (no C++ program needed)")
    args = p.parse_args()
    names = [n for n in args.robots.split(",") if n]
    for n in names:
        if n not in mjarm.Robot.bundled_names():
            p.error(f"--robots: '{n}' is not a bundled model ({', '.join(mjarm.Robot.bundled_names())})")
    if not args.no_timing and not os.access(args.bench, os.X_OK):
        p.error(f"--bench: no program at {args.bench} (make bench-peers builds it; or --no-timing)")

    rng = np.random.default_rng(args.seed)
    report = {
        "peer": "pinocchio", "versions": common.versions("pin"), "machine": common.machine(),
        "protocol": [
            f"robots {', '.join(names)}, frame {FRAME}; mjarm loads the bundled MJCF, Pinocchio "
            "the same file (includes inlined) with pin.buildModelFromMJCF",
            f"{args.configurations} configurations per robot, numpy default_rng({args.seed}): "
            "q uniform within the joint limits, q̇ uniform in ±2 rad/s, q̈ uniform in ±10 rad/s²",
            "agreement: largest absolute difference over every configuration of the frame pose "
            "(position [m] and rotation matrix entries), the world-aligned Jacobian "
            "(Pinocchio LOCAL_WORLD_ALIGNED; rows linear first on both sides), τ [N·m] "
            "(Pinocchio rnea; mjarm ChainDynamics.inverse_dynamics = M·q̈ + h after mj_forward) "
            f"and M [kg·m²] (Pinocchio crba, symmetrized; mjarm mass_matrix); tolerance {TOLERANCE}",
            "timing in C++ (bench/peers/pinocchio_bench.cpp: both libraries in one program, the "
            "same compiler, flags and Eigen), one call per configuration, cycled; "
            f"{args.repetitions} repetitions of ≥ {args.min_time} s per call, randomly interleaved, "
            f"median; {args.clock} clock (Google Benchmark's "
            f"{'cpu_time' if args.clock == 'cpu' else 'real_time'})",
            "mjarm's dynamics read the state MuJoCo computes: its rnea and crba rows include the "
            "MuJoCo stages they need (mj_kinematics, mj_comPos, mj_makeM, and mj_comVel + mj_rne "
            "for the bias); the rows '… on a computed state' are mjarm's calls alone",
        ],
    }
    robots = []
    with tempfile.TemporaryDirectory(prefix="mjarm-peers-") as directory:
        report["agreement"] = {}
        for name in names:
            model = pinocchio_model(name, directory)
            chain = mjarm.Chain(mjarm.Robot.bundled(name), FRAME)
            qs, vs, accs = configurations(chain, args.configurations, rng)
            report["agreement"][name] = agreement(name, model, qs, vs, accs)
            robots.append({**export(model, name), "q": qs.tolist(), "v": vs.tolist(),
                           "a": accs.tolist()})
        if not all(a["within_tolerance"] for a in report["agreement"].values()):
            common.emit(args, report, format_text(report))
            sys.exit("pinocchio_side_by_side: the libraries disagree beyond the tolerance")
        if not args.no_timing:
            timing = run_timing(args, robots, directory)
            report["versions"]["pinocchio (C++ headers)"] = timing["context"]["pinocchio"]
            report["agreement_cpp"] = {n: json.loads(timing["context"][f"agreement/{n}"])
                                       for n in names}
            report["machine"]["load_average_after"] = common.machine()["load_average"]
            report["timing"] = timing_rows(timing, names, args.clock)
    common.emit(args, report, format_text(report))


def timing_rows(timing, names, clock):
    key = "cpu_time" if clock == "cpu" else "real_time"
    # the median of the repetitions (one repetition: Google Benchmark reports no aggregate)
    median = {b["run_name"]: b[key] for b in timing["benchmarks"]
              if b.get("aggregate_name") == "median" or b.get("run_type") == "iteration"}
    rows = []
    for name in names:
        for call, what in CALLS:
            ours, theirs = median[f"{name}/{call}/mjarm"], median[f"{name}/{call}/pinocchio"]
            rows.append({"robot": name, "call": call, "what": what, "mjarm_ns": ours,
                         "pinocchio_ns": theirs, "ratio": ours / theirs})
        for call, what in (("rnea_state", "τ on a computed state (inverse_dynamics alone)"),
                           ("crba_state", "M on a computed state (ChainDynamics.update alone)")):
            rows.append({"robot": name, "call": call, "what": what,
                         "mjarm_ns": median[f"{name}/{call}/mjarm"], "pinocchio_ns": None,
                         "ratio": None})
    return rows


def format_text(report):
    parts = [common.header("Pinocchio and mjarm side by side", report), "", "Agreement (largest "
             "absolute difference over the configurations):", ""]
    rows = []
    for name, a in report["agreement"].items():
        cpp = report.get("agreement_cpp", {}).get(name)
        rows.append([name, a["configurations"], f"{a['pose']:.1e}", f"{a['jacobian']:.1e}",
                     f"{a['rnea']:.1e} (of {a['largest_tau']:.0f})",
                     f"{a['crba']:.1e} (of {a['largest_M']:.2f})",
                     "yes" if a["within_tolerance"] else "**no**",
                     "—" if cpp is None else f"{max(cpp[k] for k in ('pose', 'jacobian', 'rnea', 'crba')):.1e}"])
    parts.append(common.table(["robot", "configurations", "pose", "Jacobian", "τ [N·m]",
                               "M [kg·m²]", f"≤ {TOLERANCE}", "C++ rebuild, worst"], rows))
    if "timing" in report:
        parts += ["", "Time per call (median):", ""]
        rows = []
        for r in report["timing"]:
            ratio = "—" if r["ratio"] is None else f"{r['ratio']:.2f}"
            theirs = "—" if r["pinocchio_ns"] is None else f"{r['pinocchio_ns']:.0f}"
            rows.append([r["robot"], r["what"], f"{r['mjarm_ns']:.0f}", theirs, ratio])
        parts.append(common.table(["robot", "call", "mjarm [ns]", "Pinocchio [ns]",
                                   "mjarm / Pinocchio"], rows))
    return "\n".join(parts)


if __name__ == "__main__":
    main()
