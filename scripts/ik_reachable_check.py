#!/usr/bin/env python3
"""Seeded reachable position targets for `mjarm ik`: draws N configurations uniformly inside the
joint limits of MODEL's chain, takes their site positions (`mjarm fk`) as targets and counts how
many `mjarm ik MODEL --pos x y z [EXTRA...]` solves (exit 0).

usage: scripts/ik_reachable_check.py [--mjarm build/mjarm] [--trials 20] [--seed 1] [--site S] MODEL
       [-- EXTRA...]
"""
import argparse
import json
import random
import subprocess
import sys


def run(mjarm, args):
    return subprocess.run([mjarm, *args], capture_output=True, text=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mjarm", default="build/mjarm")
    parser.add_argument("--trials", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--site", help="the chain's site (needed when MODEL has several)")
    parser.add_argument("--verbose", action="store_true", help="print every target")
    parser.add_argument("model")
    parser.add_argument("extra", nargs="*", help="more `mjarm ik` options (after --)")
    a = parser.parse_args()

    rng = random.Random(a.seed)
    site = ["--site", a.site] if a.site else []
    fk0 = json.loads(run(a.mjarm, ["fk", a.model, *site, "--json"]).stdout)
    info = json.loads(run(a.mjarm, ["info", a.model, "--json"]).stdout)
    ranges = {j["name"]: j["range"] for j in info["joints"]}
    solved = 0
    restarted = 0
    for trial in range(a.trials):
        q = [rng.uniform(*ranges[name]) for name in fk0["joints"]]
        fk = json.loads(run(a.mjarm, ["fk", a.model, *site, "--json", "--q", *map(repr, q)]).stdout)
        pos = [f"{x:.6f}" for x in fk["position"]]
        r = run(a.mjarm, ["ik", a.model, *site, "--pos", *pos, "--json", *a.extra])
        ok = r.returncode == 0
        solved += ok
        doc = json.loads(r.stdout) if r.stdout.strip() else {}
        restarted += bool(doc.get("restarts_needed"))
        if a.verbose or not ok:
            print(f"target {trial}: {' '.join(pos)} -> exit {r.returncode}, "
                  f"status {doc.get('status')}, error {doc.get('position_error')}, "
                  f"start {doc.get('start')}, restarts needed {doc.get('restarts_needed')}")
    where = f"{a.model} ({a.site})" if a.site else a.model
    print(f"{where}: {solved}/{a.trials} reachable targets solved, {restarted} after global "
          f"restarts (seed {a.seed}, options {' '.join(a.extra) or '(defaults)'})")
    return 0 if solved == a.trials else 1


if __name__ == "__main__":
    sys.exit(main())
