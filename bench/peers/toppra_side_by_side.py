#!/usr/bin/env python3
"""toppra (Pham & Pham's own Python package) and mjarm's TimeOptimalPath side by side: the same
random paths, grids and limits, the same discretization (the paper's interpolation scheme).

`mjarm bench topp --cases-out FILE` draws the seeded paths (7 joints, 5-8 waypoints, limits
log-uniform: v in [0.5, 3], a in [1, 15]), times each with TimeOptimalPath and writes one JSON line
per path (waypoints, limits, N, duration, calculation time). Here each path is rebuilt for toppra
as the same geometric path — a natural cubic spline in the cumulative chord length
(toppra.SplineInterpolator with bc_type="natural") — and timed on the same N + 1 equally spaced
grid points with JointVelocityConstraint and JointAccelerationConstraint (Interpolation), the
"seidel" solver wrapper (its fastest, in Cython) and rest to rest. The durations are compared
(toppra's from its sd_vec with s̈ constant per step, as mjarm's), and the calculation times: mjarm's
in C++ (the TimeOptimalPath constructor, steady or CPU clock as --clock), toppra's in Python
(TOPPRA construction + compute_parameterization, the same clock).

    .venv/bin/python bench/peers/toppra_side_by_side.py --mjarm build-rel/mjarm --paths 1000
"""
import argparse
import importlib.metadata
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import toppra as ta
import toppra.algorithm as algo
import toppra.constraint as constraint

CLOCKS = {"cpu": time.thread_time_ns, "wall": time.perf_counter_ns}


def toppra_case(case, clock):
    """toppra's duration and calculation time [µs] on one case of `mjarm bench topp`."""
    w = np.array(case["waypoints"])
    ss = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(w, axis=0), axis=1))])
    path = ta.SplineInterpolator(ss, w, bc_type="natural")
    v = np.array(case["max_velocity"])
    a = np.array(case["max_acceleration"])
    grid = np.linspace(0.0, ss[-1], case["grid_intervals"] + 1)
    t0 = clock()
    velocity = constraint.JointVelocityConstraint(np.stack([-v, v], axis=1))
    acceleration = constraint.JointAccelerationConstraint(
        np.stack([-a, a], axis=1), discretization_scheme=constraint.DiscretizationType.Interpolation)
    instance = algo.TOPPRA([velocity, acceleration], path, gridpoints=grid,
                           solver_wrapper="seidel", parametrizer="ParametrizeConstAccel")
    t1 = clock()
    instance.compute_parameterization(0.0, 0.0)
    t2 = clock()
    data = instance.problem_data
    if data.return_code != algo.ParameterizationReturnCode.Ok:
        return None, (t2 - t0) / 1e3, (t2 - t1) / 1e3
    sd = np.asarray(data.sd_vec)
    duration = float(np.sum(2.0 * np.diff(grid) / (sd[:-1] + sd[1:])))
    return duration, (t2 - t0) / 1e3, (t2 - t1) / 1e3


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mjarm", default="build-rel/mjarm", help="the mjarm CLI (a Release build)")
    p.add_argument("--paths", type=int, default=1000, help="random paths (default 1000)")
    p.add_argument("--seed", type=int, default=0, help="seed of the paths (default 0)")
    p.add_argument("--grid", type=int, default=100, help="grid steps N (default 100)")
    p.add_argument("--clock", choices=sorted(CLOCKS), default="cpu",
                   help="clock of the per-path times on both sides (default cpu)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    args = p.parse_args()

    with tempfile.TemporaryDirectory() as folder:
        cases_file = os.path.join(folder, "cases.jsonl")
        subprocess.run([args.mjarm, "bench", "topp", "--paths", str(args.paths), "--seed",
                        str(args.seed), "--grid", str(args.grid), "--reference-paths", "0",
                        "--refinement-paths", "0", "--clock", args.clock, "--cases-out",
                        cases_file, "--json"], check=True, stdout=subprocess.DEVNULL)
        with open(cases_file) as f:
            cases = [json.loads(line) for line in f]

    clock = CLOCKS[args.clock]
    ratios, mjarm_us, toppra_us, toppra_pass_us, failures = [], [], [], [], 0
    for case in cases:
        duration, total_us, pass_us = toppra_case(case, clock)
        if duration is None or case["status"] != "solved":
            failures += 1
            continue
        ratios.append(case["duration"] / duration)
        mjarm_us.append(case["calculation_us"])
        toppra_us.append(total_us)
        toppra_pass_us.append(pass_us)
    ratios = np.array(ratios)
    figures = {
        "paths": len(cases), "seed": args.seed, "grid_intervals": args.grid, "clock": args.clock,
        "failures": failures, "toppra_version": importlib.metadata.version("toppra"),
        "duration_ratio_min": float(ratios.min()), "duration_ratio_median": float(np.median(ratios)),
        "duration_ratio_max": float(ratios.max()),
        "mjarm_median_us": float(np.median(mjarm_us)),
        "mjarm_p95_us": float(np.percentile(mjarm_us, 95)),
        "toppra_median_us": float(np.median(toppra_us)),
        "toppra_p95_us": float(np.percentile(toppra_us, 95)),
        "toppra_passes_median_us": float(np.median(toppra_pass_us)),
        "time_ratio_median": float(np.median(np.array(toppra_us) / np.array(mjarm_us))),
    }
    if args.json:
        print(json.dumps(figures, indent=2))
        return
    print(f"{len(cases)} paths, seed {args.seed}, grid {args.grid} steps, toppra "
          f"{figures['toppra_version']} (seidel), {failures} failures on either side")
    print(f"duration mjarm/toppra: min {figures['duration_ratio_min']:.9f}, median "
          f"{figures['duration_ratio_median']:.9f}, max {figures['duration_ratio_max']:.9f}")
    print(f"time per path ({args.clock} clock): mjarm median {figures['mjarm_median_us']:.1f} µs "
          f"(p95 {figures['mjarm_p95_us']:.1f}); toppra median {figures['toppra_median_us']:.1f} "
          f"µs (p95 {figures['toppra_p95_us']:.1f}; its two passes alone "
          f"{figures['toppra_passes_median_us']:.1f}); toppra/mjarm median "
          f"{figures['time_ratio_median']:.1f}x")


if __name__ == "__main__":
    sys.exit(main())
