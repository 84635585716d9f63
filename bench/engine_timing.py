#!/usr/bin/env python3
"""Two mjarm CLIs timed side by side: the same benchmark commands, alternating A, B, A, B, …
for --rounds rounds, each figure the median over the rounds. Made for an engine upgrade (the
CLI built on the old MuJoCo against the one built on the new), so that load drifting on the
machine touches both sides alike.

Measured, per CLI:
  - IK: `mjarm bench ik ARM --samples N --clock cpu` (the TRAC-IK protocol, CPU time of the
    solving thread): success rate and mean solve time, from the mid-range and random seeds;
  - control: `mjarm bench control ARM --steps S` (closed loop with MuJoCo): the median time of
    each controller's step, and one mj_step with and without operational-space control;
  - environment: `mjarm bench env --rounds 1` (the reach task): µs per environment step, the
    bare mj_step calls of the same physics, and the overhead between them.

usage: engine_timing.py A_MJARM B_MJARM [--labels A,B] [--rounds 5] [--samples 2000]
                        [--steps 20000] [--arms panda,iiwa14] [--json]
Progress goes to stderr on a terminal only.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys


def run_json(binary, args):
    result = subprocess.run([binary, *args, "--json"], text=True, capture_output=True)
    if result.returncode != 0:
        sys.exit(f"engine_timing: `{binary} {' '.join(args)}` failed ({result.returncode}):\n"
                 f"{result.stderr}")
    return json.loads(result.stdout)


def figures(binary, arms, samples, steps):
    """One round of every benchmark: {figure name: value}."""
    out = {}
    for arm in arms:
        ik = run_json(binary, ["bench", "ik", arm, "--samples", str(samples), "--clock", "cpu"])
        for r in ik["runs"]:
            key = f"ik {arm} {r['seed_mode']}"
            out[f"{key} success [%]"] = 100.0 * r["success_rate"]
            out[f"{key} mean [µs]"] = 1000.0 * r["mean_time_ms"]
        control = run_json(binary, ["bench", "control", arm, "--steps", str(steps)])
        for c in control["controllers"]:
            out[f"control {arm} {c['name']} median [µs]"] = c["median_us"]
        for k, v in control["step_us"].items():
            out[f"control {arm} {k} [µs]"] = v
    env = run_json(binary, ["bench", "env", "--rounds", "1"])
    out["env reach step [µs]"] = env["env_us_per_step"]
    out["env reach bare mj_step calls [µs]"] = env["bare_us_per_step"]
    out["env reach overhead [%]"] = 100.0 * env["overhead"]
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--labels", default="A,B")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--samples", type=int, default=2000)
    parser.add_argument("--steps", type=int, default=20000)
    parser.add_argument("--arms", default="panda,iiwa14")
    parser.add_argument("--json", action="store_true")
    o = parser.parse_args()
    if o.rounds < 1 or o.samples < 1 or o.steps < 1:
        sys.exit("engine_timing: --rounds, --samples and --steps must be at least 1")
    labels = o.labels.split(",")
    if len(labels) != 2:
        sys.exit("engine_timing: --labels takes two names, e.g. 2.2.2,4.0.1")
    arms = o.arms.split(",")
    progress = sys.stderr.isatty()
    rounds = {labels[0]: [], labels[1]: []}
    load_before = os.getloadavg()
    for i in range(o.rounds):
        for label, binary in zip(labels, [o.a, o.b]):
            if progress:
                print(f"\rround {i + 1}/{o.rounds}: {label}   ", end="", file=sys.stderr, flush=True)
            rounds[label].append(figures(binary, arms, o.samples, o.steps))
    if progress:
        print(file=sys.stderr)
    medians = {label: {k: statistics.median(r[k] for r in rs) for k in rs[0]}
               for label, rs in rounds.items()}
    report = {"labels": labels, "binaries": [o.a, o.b], "rounds": o.rounds,
              "samples": o.samples, "steps": o.steps, "arms": arms,
              "load_before": load_before, "load_after": os.getloadavg(), "medians": medians}
    if o.json:
        print(json.dumps(report, indent=1))
        return
    a, b = medians[labels[0]], medians[labels[1]]
    print(f"median of {o.rounds} alternating rounds; load average before "
          f"{load_before[0]:.2f}, after {report['load_after'][0]:.2f}")
    print(f"| figure | {labels[0]} | {labels[1]} | {labels[1]} / {labels[0]} |")
    print("|---|---|---|---|")
    for key in a:
        if key not in b:
            continue
        ratio = f"{b[key] / a[key]:.2f}" if a[key] and "[%]" not in key else ""
        print(f"| {key} | {a[key]:.3g} | {b[key]:.3g} | {ratio} |")


if __name__ == "__main__":
    main()
