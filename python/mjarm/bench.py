"""Binding-overhead benchmark: ``python3 -m mjarm.bench [--cpp PATH] [--json]``.

Times, from Python, the calls that bench/python_binding_bench.cpp times in C++ on the same
inputs (its comment states the protocol): forward kinematics, a position IK solve, one
operational-space controller step (``compute(data, ref)``, a new array per call, and
``compute(data, ref, out)``, written into a preallocated array as the C++ loop writes into its
command), a loop of Simulation.tick (real-time factor), and an environment step
(Environment.step: the cheapest configuration, one physics step a call, where the binding's share
shows, and the default reach environment); also the tick loop with the same joint PD written as a
Python Controller, and what the GIL's release in VectorEnvironment.step buys: two Python threads
stepping an environment each against the same work one after the other (beside the same work on
mjarm's own 2-thread pool, which the GIL does not touch; both need a free core to exceed 1x). With --cpp it runs the C++
benchmark program and prints the per-call overhead (Python − C++) and the ratio of real-time
factors; with --repeat N it measures both sides N times, one after the other, and each overhead
is the median of the N differences. Python figures are medians of --rounds rounds.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import threading
import time

import numpy as np

import mjarm

# the clock of the per-call figures: wall time, or this thread's CPU time (--clock cpu, for a
# shared machine: time the thread waits for a core is not counted, on either side)
CLOCK = [time.perf_counter]


def configurations(chain):
    lo, hi = chain.lower, chain.upper
    qs = []
    for k in range(64):
        q = np.empty(chain.size)
        for i in range(chain.size):
            x = 0.6180339887 * (k + 1) + 0.4142135624 * (i + 1)
            q[i] = lo[i] + (hi[i] - lo[i]) * (0.05 + 0.9 * (x - math.floor(x)))
        qs.append(q)
    return qs


def per_call(fn, args, rounds, calls):
    """Median over rounds of the mean time per call [s]."""
    results = []
    n = len(args)
    for _ in range(rounds):
        start = CLOCK[0]()
        for i in range(calls):
            fn(args[i % n])
        results.append((CLOCK[0]() - start) / calls)
    return statistics.median(results)


def step_per_call(compute, data, reference, out, rounds, calls):
    """Median over rounds of the mean time per controller step [s]: the call as a user's control
    loop makes it, compute(data, reference) (a new array each call) or, with out, compute(data,
    reference, out) (the command written into out)."""
    results = []
    for _ in range(rounds):
        start = CLOCK[0]()
        if out is None:
            for _ in range(calls):
                compute(data, reference)
        else:
            for _ in range(calls):
                compute(data, reference, out)
        results.append((CLOCK[0]() - start) / calls)
    return statistics.median(results)


class PythonPd(mjarm.Controller):
    def __init__(self, chain, kp, kd):
        mjarm.Controller.__init__(self, chain, mjarm.CommandKind.torque, "py-pd")
        self.qa = chain.qpos_addresses
        self.da = chain.dof_addresses
        self.kp, self.kd = kp, kd

    def compute(self, data, reference):
        return (self.kp * (reference.joint.q - data.qpos[self.qa])
                + self.kd * (reference.joint.qd - data.qvel[self.da]) + data.qfrc_bias[self.da])


def tick_loop_rtf(robot, chain, controller, ticks, rounds):
    sim = mjarm.Simulation(robot, mjarm.SimulationOptions(mjarm.SimulationMode.torque, 0.0))
    sim.add_controller(controller)
    ref = mjarm.Reference()
    ref.joint.q = chain.gather(robot.keyframe_qpos("home"))
    ref.joint.qd = np.zeros(chain.size)
    ref.joint.qdd = np.zeros(chain.size)
    rtfs = []
    for _ in range(rounds):
        sim.reset("home")
        tick = sim.tick
        start = time.perf_counter()
        for _ in range(ticks):
            tick(ref)
        rtfs.append(sim.time / (time.perf_counter() - start))
    return statistics.median(rtfs)


def measure(rounds, calls, ticks):
    panda = mjarm.Robot.bundled("panda")
    chain = mjarm.Chain(panda, "attachment_site")
    kin = mjarm.ChainKinematics(chain)
    qs = configurations(chain)
    out = {"fk_us": 1e6 * per_call(kin.update, qs, rounds, calls)}
    targets = [kin.update(q).p for q in qs]
    seed = chain.gather(panda.keyframe_qpos("home"))
    ik = mjarm.PositionIk(chain)
    out["ik_us"] = 1e6 * per_call(lambda p: ik.solve(p, seed), targets, rounds, max(calls // 20, 64))

    robot = mjarm.Robot.bundled("panda_torque")
    tchain = mjarm.Chain(robot, "attachment_site")
    data = robot.make_data()
    data.qpos[:] = robot.keyframe_qpos("home")
    data.forward()
    ref = mjarm.Reference()
    home_q = tchain.gather(robot.keyframe_qpos("home"))
    X = mjarm.forward_kinematics(tchain, home_q)
    X.p = X.p + [0.05, 0.0, 0.0]
    ref.task.X_WE = X
    ref.joint.q = home_q
    ref.joint.qd = np.zeros(7)
    ref.joint.qdd = np.zeros(7)
    osc = mjarm.OperationalSpaceController(tchain)
    out["controller_us"] = 1e6 * step_per_call(osc.compute, data, ref, None, rounds, calls)
    out["controller_out_us"] = 1e6 * step_per_call(osc.compute, data, ref, np.zeros(7), rounds, calls)
    out["tick_rtf"] = tick_loop_rtf(robot, tchain, mjarm.JointPdController(tchain), ticks, rounds)
    gains = mjarm.JointPdOptions().gains
    out["tick_rtf_python_controller"] = tick_loop_rtf(
        robot, tchain, PythonPd(tchain, gains.kp[0], gains.kd[0]), ticks, rounds)
    return out


def env_step(env, rounds, calls):
    """Median over rounds of the thread CPU time per Environment.step [s], reset(0) after LAST
    (timed too), as bench/python_binding_bench.cpp's env_loop. CPU time, not wall time: on a
    shared machine the wall time of a 15-200 us call varies by more than the binding costs."""
    action = np.zeros(env.action_spec().shape)
    step, reset = env.step, env.reset
    results = []
    for _ in range(rounds):
        reset(0)
        start = time.thread_time()
        for _ in range(calls):
            if step(action).last():
                reset(0)
        results.append((time.thread_time() - start) / calls)
    return statistics.median(results)


ENV_KEYS = ("env_step_us", "env_step_reach_us")


def env_figures(rounds, calls, cpp_path):
    """The environment steps, paired: each round runs the C++ side's two environment benchmarks
    (with cpp_path) and right after one Python round of each, so that a change of the machine's
    load moves both sides of a pair; the overhead is the median of the paired differences."""
    cheap = mjarm.Environment("reach", action_space="joint_torques", control_period=0.002,
                              time_limit=2.0)
    reach = mjarm.Environment("reach")
    py, cpp = {k: [] for k in ENV_KEYS}, {k: [] for k in ENV_KEYS}
    for _ in range(rounds):
        if cpp_path:
            figures = cpp_figures(cpp_path, 0.2, benchmark_filter="^BM_EnvStep")
            for k in ENV_KEYS:
                cpp[k].append(figures[k])
        py["env_step_us"].append(1e6 * env_step(cheap, 1, calls))
        py["env_step_reach_us"].append(1e6 * env_step(reach, 1, max(calls // 20, 500)))
    out = {"python": {k: statistics.median(v) for k, v in py.items()}, "cpp": {}, "overhead": {}}
    if cpp_path:
        for k in ENV_KEYS:
            out["cpp"][k] = statistics.median(cpp[k])
            out["overhead"][k] = statistics.median(p - c for p, c in zip(py[k], cpp[k]))
    out["rounds"] = {"python": py, "cpp": cpp}
    return out


def threads_figures(rounds, seconds=0.2):
    """Speed-ups of stepping 2 x 4 reach environments: from two Python threads at once, and on
    mjarm's own 2-thread pool, each against the same steps one after the other (wall time, best
    of the rounds: a shared machine's other work only ever slows a round)."""
    envs = [mjarm.VectorEnvironment("reach", 4, 1, time_limit=100.0, seed=s) for s in (1, 2)]
    pool = mjarm.VectorEnvironment("reach", 8, 2, time_limit=100.0, seed=3)
    actions, actions8 = np.zeros((4, 6)), np.zeros((8, 6))
    for e in envs + [pool]:
        e.reset()

    def run(e, a, steps):
        for _ in range(steps):
            e.step(a)

    start = time.perf_counter()
    run(envs[0], actions, 10)
    steps = max(10, int(seconds / ((time.perf_counter() - start) / 10)))
    python_threads, pool_threads = [], []
    for _ in range(rounds):
        start = time.perf_counter()
        run(envs[0], actions, steps)
        run(envs[1], actions, steps)
        serial = time.perf_counter() - start
        threads = [threading.Thread(target=run, args=(e, actions, steps)) for e in envs]
        start = time.perf_counter()
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        python_threads.append(serial / (time.perf_counter() - start))
        start = time.perf_counter()
        run(pool, actions8, steps)
        pool_threads.append(serial / (time.perf_counter() - start))
    return {"two_python_threads_speedup": max(python_threads),
            "pool_two_threads_speedup": max(pool_threads), "steps_per_thread": steps}


def cpp_figures(path, min_time, field="real_time", benchmark_filter=None):
    command = [path, "--benchmark_format=json", f"--benchmark_min_time={min_time}"]
    if benchmark_filter:
        command.append(f"--benchmark_filter={benchmark_filter}")
    result = subprocess.run(command, capture_output=True, text=True, check=True)
    figures = {}
    for b in json.loads(result.stdout)["benchmarks"]:
        scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3}[b["time_unit"]]
        name = b["name"]
        if name == "BM_Fk":
            figures["fk_us"] = b[field] * scale
        elif name == "BM_PositionIk":
            figures["ik_us"] = b[field] * scale
        elif name == "BM_ControllerStep":
            figures["controller_us"] = b[field] * scale
        elif name == "BM_TickLoop":
            figures["tick_rtf"] = b["rtf"]
        elif name == "BM_EnvStep":  # CPU time, as the Python side (env_step)
            figures["env_step_us"] = b["cpu_time"] * scale
        elif name == "BM_EnvStepReach":
            figures["env_step_reach_us"] = b["cpu_time"] * scale
    return figures


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m mjarm.bench", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cpp", help="path of bench_python_binding (the C++ side)")
    parser.add_argument("--rounds", type=int, default=5, help="rounds per figure (median), 1..100")
    parser.add_argument("--calls", type=int, default=20000, help="calls per round, 100..10^7")
    parser.add_argument("--ticks", type=int, default=5000, help="ticks per loop round, 100..10^7")
    parser.add_argument("--repeat", type=int, default=1,
                        help="with --cpp: measure Python then C++ this many times, 1..50, and "
                             "give each overhead as the median of the pairs' differences (a load "
                             "change between the two sides then moves one pair, not the figure)")
    parser.add_argument("--clock", choices=("wall", "cpu"), default="wall",
                        help="per-call figures in wall time (default) or the thread's CPU time, "
                             "Google Benchmark's cpu_time on the C++ side (the tick loop's "
                             "real-time factors stay in wall time)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    if not 1 <= args.rounds <= 100 or not 100 <= args.calls <= 10**7 or not 100 <= args.ticks <= 10**7:
        parser.error("--rounds must be in 1..100, --calls and --ticks in 100..10^7")
    if not 1 <= args.repeat <= 50:
        parser.error("--repeat must be in 1..50")
    if args.cpp and not os.access(args.cpp, os.X_OK):
        parser.error(f"--cpp: {args.cpp} is not an executable")
    if args.clock == "cpu":
        CLOCK[0] = time.thread_time
    load_start = os.getloadavg()[0]
    pairs = []
    for _ in range(args.repeat if args.cpp else 1):
        py = measure(args.rounds, args.calls, args.ticks)
        field = "cpu_time" if args.clock == "cpu" else "real_time"
        pairs.append((py, cpp_figures(args.cpp, 0.5, field, "-BM_EnvStep") if args.cpp else {}))
    env = env_figures(args.rounds, args.calls, args.cpp)
    threads = threads_figures(args.rounds)
    load = [load_start, os.getloadavg()[0]]  # 1-minute load average before and after
    keys = [("fk_us", "fk_us"), ("ik_us", "ik_us"), ("controller_us", "controller_us"),
            ("controller_out_us", "controller_us")]  # (Python figure, the C++ figure it matches)
    py = {k: statistics.median(p[k] for p, _ in pairs) for k in pairs[0][0]}
    cpp = {k: statistics.median(c[k] for _, c in pairs) for k in pairs[0][1]}
    overhead = {k: statistics.median(p[k] - c[ck] for p, c in pairs) for k, ck in keys if ck in cpp}
    py.update(env["python"])
    cpp.update(env["cpp"])
    overhead.update(env["overhead"])
    if "tick_rtf" in cpp:
        overhead["tick_rtf_ratio"] = statistics.median(c["tick_rtf"] / p["tick_rtf"] for p, c in pairs)
    if args.json:
        print(json.dumps({"python": py, "cpp": cpp, "overhead": overhead, "repeat": len(pairs),
                          "clock": args.clock, "load_average": load,
                          "env_rounds": env["rounds"], "threads": threads}))
        return 0
    print(f"{args.clock} clock; load average (1 min): {load[0]:.2f} at the start, {load[1]:.2f} at the end"
          + (f"; medians of {len(pairs)} Python/C++ pairs" if len(pairs) > 1 else ""))
    print(f"{'call':34} {'Python':>12} {'C++':>12} {'overhead':>12}")
    labels = ("FK (ChainKinematics.update)", "PositionIk.solve", "OSC controller step",
              "  ... compute(data, ref, out)")
    for (key, ckey), label in zip(keys, labels):
        c = cpp.get(ckey)
        print(f"{label:34} {py[key]:10.3f}us "
              + (f"{c:10.3f}us {overhead[key]:10.3f}us" if c else ""))
    c = cpp.get("tick_rtf")
    print(f"{'Simulation.tick loop (RTF)':34} {py['tick_rtf']:11.1f}x "
          + (f"{c:11.1f}x {overhead['tick_rtf_ratio']:10.2f}x slower" if c else ""))
    print(f"{'  ... with a Python Controller':34} {py['tick_rtf_python_controller']:11.1f}x")
    for key, label in (("env_step_us", "Environment.step (1 physics step)"),
                       ("env_step_reach_us", "Environment.step (reach defaults)")):
        c, d = cpp.get(key), overhead.get(key)
        print(f"{label:34} {py[key]:10.3f}us " + (f"{c:10.3f}us {d:10.3f}us (CPU time, "
                                                    "median of paired rounds)" if c else ""))
    print(f"{'two Python threads stepping':34} {threads['two_python_threads_speedup']:11.2f}x of "
          f"one (mjarm's 2-thread pool: {threads['pool_two_threads_speedup']:.2f}x; best of "
          f"{args.rounds}, {threads['steps_per_thread']} batch steps of 4 reach environments)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
