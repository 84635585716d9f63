"""A Python task's step overhead: ``python3 -m mjarm.bench_task [--steps N] [--rounds R] [--json]``.

Protocol: the built-in reach task (C++) and the same task written in Python (``PyReach`` below:
the same robot and chain, the same start — the ``home`` keyframe with each joint perturbed by at
most 0.05 rad —, the same target box, observations ``target`` and ``target_offset``, reward
−distance, termination within 1 cm) run in two environments with identical options (the
``ee_velocities`` action space, 2 s episodes, the reach task's default observations). Each round
steps each environment N times with the same seeded uniform random actions, resetting at the end
of an episode (resets excluded from nothing: both pay theirs), one environment after the other;
a figure is the median over rounds of the mean wall time per step. The overhead is Python − C++
per step, and the ratio Python / C++. The Python task's hooks (map none, observe twice,
reward, terminated, the episode's generator at reset) each take the GIL and build a context.
"""
import argparse
import json
import statistics
import sys
import time

import numpy as np

import mjarm


class PyReach(mjarm.EnvTask):
    """The reach task written in Python on the built-in one's robot and chain."""
    name = "py_reach"
    description = "the reach task, in Python"

    def __init__(self, robot, chain):
        super().__init__(robot, chain)
        self.center = np.array([0.45, 0.0, 0.45])
        self.half_width = np.array([0.15, 0.25, 0.15])
        self.target = self.center

    def observation_specs(self):
        return [mjarm.ArraySpec("target", [3], self.center - self.half_width,
                                self.center + self.half_width),
                mjarm.ArraySpec("target_offset", [3])]

    def default_observations(self):
        return ["joint_positions", "joint_velocities", "ee_pose", "target", "target_offset"]

    def initialize_episode(self, sim, rng):
        sim.reset("home")
        qpos = np.array(sim.qpos)
        chain = self.chain
        for i, address in enumerate(chain.qpos_addresses):
            qpos[address] = np.clip(qpos[address] + rng.uniform(-0.05, 0.05),
                                    chain.lower[i], chain.upper[i])
        self.target = self.center + rng.uniform(-1.0, 1.0, 3) * self.half_width
        sim.set_state(qpos, np.zeros(sim.robot.nv))

    def observe(self, name, context):
        return self.target if name == "target" else self.target - context.X_WE.p

    def reward(self, context):
        return -float(np.linalg.norm(context.X_WE.p - self.target))

    def terminated(self, context):
        return float(np.linalg.norm(context.X_WE.p - self.target)) <= 0.01


def time_per_step(env, actions):
    """Mean wall time per step [s] over the actions (a reset at each episode's end)."""
    ts = env.reset(seed=1)
    start = time.perf_counter()
    for action in actions:
        ts = env.reset() if ts.last() else env.step(action)
    return (time.perf_counter() - start) / len(actions)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m mjarm.bench_task", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=2000, help="steps per round, 10..10^6")
    parser.add_argument("--rounds", type=int, default=5, help="rounds (median), 1..100")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    if not 10 <= args.steps <= 10**6 or not 1 <= args.rounds <= 100:
        parser.error("--steps must be in 10..10^6 and --rounds in 1..100")
    options = dict(action_space="ee_velocities", time_limit=2.0)
    cpp = mjarm.Environment("reach", **options)
    py = mjarm.Environment(PyReach(cpp.robot, cpp.chain), **options)
    spec = cpp.action_spec()
    actions = np.random.default_rng(0).uniform(spec.minimum, spec.maximum,
                                               (args.steps, spec.minimum.size))
    cpp_times, py_times = [], []
    for round_ in range(args.rounds):
        cpp_times.append(time_per_step(cpp, actions))
        py_times.append(time_per_step(py, actions))
        if not args.json and sys.stderr.isatty():
            print(f"\rround {round_ + 1}/{args.rounds}", end="", file=sys.stderr, flush=True)
    if not args.json and sys.stderr.isatty():
        print(file=sys.stderr)
    c, p = statistics.median(cpp_times), statistics.median(py_times)
    figures = {"steps": args.steps, "rounds": args.rounds, "cpp_us_per_step": c * 1e6,
               "python_us_per_step": p * 1e6, "overhead_us_per_step": (p - c) * 1e6,
               "ratio": p / c}
    if args.json:
        print(json.dumps(figures))
    else:
        print(f"reach task, ee_velocities, {args.steps} steps x {args.rounds} rounds (median):")
        print(f"  C++ task    {c * 1e6:9.1f} us/step")
        print(f"  Python task {p * 1e6:9.1f} us/step")
        print(f"  overhead    {(p - c) * 1e6:9.1f} us/step  ({p / c:.2f}x)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
