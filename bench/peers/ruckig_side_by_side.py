#!/usr/bin/env python3
"""Ruckig and mjarm's JerkLimitedGenerator side by side: time-synchronized, jerk-limited
trajectories from the same random states to the same random targets, starts beyond the limits
included.

Cases are drawn as `mjarm bench otg` draws them (docs/trajectory_otg.md), here with NumPy: per
DoF, limits log-uniform (v in [0.2, 4], a in [0.3, 8], j in [0.5, 40]); positions in [-3, 3];
targets within the limits and reachable without overshoot (a fifth at rest, a tenth with zero
acceleration); starts within the limits and startable (a fifth at rest), except a share of DoFs
(--beyond, 10 %) that start beyond their limits (up to 1.6x v_max and a_max) and must brake first.

Both libraries get each case (Ruckig's defaults: time synchronization, continuous durations,
braking from beyond the limits). The durations are compared (equal within 1e-8 relative), and
every trajectory is checked, sampled and refined between samples: it ends on the target (1e-8),
its jerk stays within the limits, and once a DoF is startable (within its limits, braking done)
its velocity and acceleration stay within them (1e-9 relative; velocity peaks found where the
acceleration changes sign, acceleration peaks where it turns). A shorter duration counts only with
a feasible trajectory. Timing is from Python on both sides (neither wheel ships the C++ of both):
each call pays one binding call, which a call on a case already at its target (a floor: the
binding and the input checks) shows for each side.
"""
import os
import sys

import numpy as np
from ruckig import InputParameter, Result, Ruckig, Trajectory

import mjarm

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

SLACK = 1e-12           # the generator's own slack on the startable/reachable tests
EQUAL = 1e-8            # durations equal within this, relative to max(1, T)
LIMIT_TOLERANCE = 1e-9  # relative limit excess allowed after the brake
END_TOLERANCE = 1e-8    # |Δp|, |Δv|, |Δa| at the end, relative to max(1, |target|)
SAMPLES = 600


def startable(v, a, lim):
    vmax, amax, jmax = lim[..., 0] * (1 + SLACK), lim[..., 1] * (1 + SLACK), lim[..., 2]
    return (np.abs(a) <= amax) & (np.abs(v) <= vmax) & (np.abs(v + a * np.abs(a) / (2 * jmax)) <= vmax)


def reachable(v, a, lim):
    vmax, amax, jmax = lim[..., 0] * (1 + SLACK), lim[..., 1] * (1 + SLACK), lim[..., 2]
    return (np.abs(a) <= amax) & (np.abs(v) <= vmax) & (np.abs(v - a * np.abs(a) / (2 * jmax)) <= vmax)


class Cases:
    """The distribution of `mjarm bench otg`'s cases (trajectory/otg/validation/protocol.cpp)."""

    def __init__(self, rng, dofs, beyond_share):
        self.rng, self.dofs, self.beyond_share = rng, dofs, beyond_share

    def unit(self):
        return self.rng.uniform(-1.0, 1.0)

    def log_uniform(self, lo, hi):
        return lo * (hi / lo) ** (0.5 * (self.unit() + 1.0))

    def target(self, lim):
        while True:
            s = np.array([3.0 * self.unit(), lim[0] * self.unit(), lim[1] * self.unit()])
            kind = self.rng.uniform()
            if kind < 0.2:
                s[1] = s[2] = 0.0
            elif kind < 0.3:
                s[2] = 0.0
            if reachable(s[1], s[2], lim):
                return s

    def start(self, lim, beyond):
        scale = 1.6 if beyond else 1.0
        while True:
            s = np.array([3.0 * self.unit(), scale * lim[0] * self.unit(), scale * lim[1] * self.unit()])
            if not beyond and self.rng.uniform() < 0.2:
                s[1] = s[2] = 0.0
            if beyond != bool(startable(s[1], s[2], lim)):
                return s

    def draw(self):
        lim = np.array([[self.log_uniform(0.2, 4.0), self.log_uniform(0.3, 8.0),
                         self.log_uniform(0.5, 40.0)] for _ in range(self.dofs)])
        beyond = self.rng.uniform(size=self.dofs) < self.beyond_share
        start = np.array([self.start(lim[i], beyond[i]) for i in range(self.dofs)])
        target = np.array([self.target(lim[i]) for i in range(self.dofs)])
        return lim, start, target, beyond


def refine(f, lo, hi, maximize):
    """Golden-section search of the largest f on [lo, hi] (maximize), or bisection of a sign
    change of f (returns the root)."""
    if maximize:
        g = 0.5 * (5 ** 0.5 - 1)
        a, b = lo, hi
        c, d = b - g * (b - a), a + g * (b - a)
        fc, fd = f(c), f(d)
        for _ in range(50):
            if fc > fd:
                b, d, fd = d, c, fc
                c = b - g * (b - a)
                fc = f(c)
            else:
                a, c, fc = c, d, fd
                d = a + g * (b - a)
                fd = f(d)
        return max(fc, fd, f(lo), f(hi))
    flo = f(lo)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if (f(mid) > 0) == (flo > 0):
            lo, flo = mid, f(mid)
        else:
            hi = mid
    return 0.5 * (lo + hi)


def check(state_at, duration, lim, target):
    """Checks one trajectory (state_at(t) -> (n, 3) array of p, v, a). Returns (feasible, worst
    relative limit excess after the brake, end error, jerk excess)."""
    ts = np.linspace(0.0, duration, SAMPLES + 1)
    S = np.array([state_at(t) for t in ts])
    V, A = S[:, :, 1], S[:, :, 2]
    vmax, amax, jmax = lim[:, 0], lim[:, 1], lim[:, 2]
    end = np.max(np.abs(S[-1] - target) / np.maximum(1.0, np.abs(target)))
    dt = np.diff(ts)[:, None]
    jerk = float(np.max(np.abs(np.diff(A, axis=0)) / np.where(dt > 0, dt, 1.0) / jmax)) - 1.0 \
        if duration > 0 else -1.0
    excess = 0.0
    ok = startable(V, A, lim[None, :, :])
    for d in range(lim.shape[0]):
        inside = np.flatnonzero(ok[:, d])
        if inside.size == 0:
            return False, np.inf, end, jerk
        k0 = inside[0]
        excess = max(excess, np.max(np.abs(V[k0:, d])) / vmax[d] - 1, np.max(np.abs(A[k0:, d])) / amax[d] - 1)
        for k in range(k0, SAMPLES):
            # a velocity peak between two samples: where the acceleration changes sign
            if A[k, d] * A[k + 1, d] < 0:
                t = refine(lambda t: state_at(t)[d, 2], ts[k], ts[k + 1], False)
                excess = max(excess, abs(state_at(t)[d, 1]) / vmax[d] - 1)
            # an acceleration peak: |a| turns around between the neighbouring samples (not along
            # a hold, where it is constant and sampled)
            here, before, after = abs(A[k, d]), abs(A[k - 1, d]), abs(A[k + 1, d])
            if k > k0 and here >= before and here >= after and (here > before or here > after):
                peak = refine(lambda t: abs(state_at(t)[d, 2]), ts[k - 1], ts[k + 1], True)
                excess = max(excess, peak / amax[d] - 1)
    feasible = excess <= LIMIT_TOLERANCE and end <= END_TOLERANCE and jerk <= 1e-6
    return feasible, excess, end, jerk


class MjarmSide:
    name = "mjarm"

    def prepare(self, lim, start, target):
        self.gen = mjarm.JerkLimitedGenerator(lim)
        self.args = (np.ascontiguousarray(start), np.ascontiguousarray(target))

    def calculate(self):
        return self.gen.calculate(*self.args)

    def result(self, r):
        ok = r.status in (mjarm.OtgStatus.working, mjarm.OtgStatus.finished)
        return ok, r.duration

    def state_at(self, t):
        return self.gen.at(t)[:, :3]


class RuckigSide:
    name = "ruckig"

    def __init__(self, dofs):
        self.otg, self.inp, self.traj = Ruckig(dofs), InputParameter(dofs), Trajectory(dofs)

    def prepare(self, lim, start, target):
        inp = self.inp
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = (lim[:, k].tolist() for k in range(3))
        inp.current_position, inp.current_velocity, inp.current_acceleration = (
            start[:, k].tolist() for k in range(3))
        inp.target_position, inp.target_velocity, inp.target_acceleration = (
            target[:, k].tolist() for k in range(3))

    def calculate(self):
        return self.otg.calculate(self.inp, self.traj)

    def result(self, r):
        return r in (Result.Working, Result.Finished), self.traj.duration

    def state_at(self, t):
        return np.array(self.traj.at_time(t)).T


def time_calls(side, clock, calls):
    start = clock()
    for _ in range(calls):
        side.calculate()
    return (clock() - start) / calls


def main():
    p = common.parser(__doc__)
    p.add_argument("--cases", type=common.positive(int), default=1000,
                   help="random cases (default 1000)")
    p.add_argument("--dofs", type=common.positive(int), default=7, help="DoFs per case (default 7)")
    p.add_argument("--beyond", type=float, default=0.1,
                   help="share of DoFs starting beyond their limits (default 0.1)")
    p.add_argument("--calls", type=common.positive(int), default=5,
                   help="timed calls per case and library, back to back (default 5)")
    args = p.parse_args()
    if not 0.0 <= args.beyond <= 1.0:
        p.error("--beyond: expected a share in [0, 1]")
    clock = common.CLOCKS[args.clock]
    rng = np.random.default_rng(args.seed)
    cases = Cases(rng, args.dofs, args.beyond)
    sides = [MjarmSide(), RuckigSide(args.dofs)]
    report = {
        "peer": "ruckig", "versions": common.versions("ruckig"), "machine": common.machine(),
        "protocol": [
            f"{args.cases} cases of {args.dofs} DoFs, numpy default_rng({args.seed}), drawn as "
            f"`mjarm bench otg` draws them; {args.beyond:.0%} of DoFs start beyond their limits",
            "mjarm JerkLimitedGenerator.calculate(current, target) against Ruckig.calculate(input, "
            "trajectory) (time synchronization, continuous durations: Ruckig's defaults)",
            f"durations equal within {EQUAL} × max(1, T); each trajectory checked at {SAMPLES + 1} "
            f"instants and refined between them: end on target ({END_TOLERANCE}), jerk within "
            f"its limits, velocity and acceleration within theirs ({LIMIT_TOLERANCE} relative) "
            "from the first instant each DoF is startable on; a shorter duration counts with a "
            "feasible trajectory",
            f"time per calculation from Python, {args.calls} calls back to back per case and "
            "library, the two libraries alternating which goes first; "
            f"{args.clock} clock; a call already at its target shows each binding's floor",
        ],
    }
    stats = {s.name: {"failed": 0, "infeasible": 0, "times": [], "worst_excess": 0.0,
                      "worst_end": 0.0} for s in sides}
    compare = {"within": {"equal": 0, "mjarm_shorter": [0, 0], "ruckig_shorter": [0, 0], "cases": 0},
               "beyond": {"equal": 0, "mjarm_shorter": [0, 0], "ruckig_shorter": [0, 0], "cases": 0}}
    largest = {"mjarm_shorter": 0.0, "ruckig_shorter": 0.0}
    examples = []
    progress = common.Progress("cases", args.cases)
    for c in range(args.cases):
        lim, start, target, beyond = cases.draw()
        kind = "beyond" if beyond.any() else "within"
        compare[kind]["cases"] += 1
        outcome = {}
        order = sides if c % 2 == 0 else sides[::-1]
        for side in order:
            side.prepare(lim, start, target)
            stats[side.name]["times"].append(time_calls(side, clock, args.calls))
        for side in sides:
            side.prepare(lim, start, target)
            ok, duration = side.result(side.calculate())
            st = stats[side.name]
            if not ok:
                st["failed"] += 1
                outcome[side.name] = None
                continue
            feasible, excess, end, _ = check(side.state_at, duration, lim, target)
            st["infeasible"] += 0 if feasible else 1
            st["worst_excess"] = max(st["worst_excess"], excess)
            st["worst_end"] = max(st["worst_end"], end)
            outcome[side.name] = (duration, feasible)
        if outcome["mjarm"] and outcome["ruckig"]:
            (tm, fm), (tr, fr) = outcome["mjarm"], outcome["ruckig"]
            if abs(tm - tr) <= EQUAL * max(1.0, tm, tr):
                compare[kind]["equal"] += 1
            else:
                key, feasible = ("mjarm_shorter", fm) if tm < tr else ("ruckig_shorter", fr)
                compare[kind][key][0 if feasible else 1] += 1
                largest[key] = max(largest[key], abs(tm - tr) / max(tm, tr))
                if len(examples) < 5:
                    examples.append({"case": c, "mjarm_s": tm, "ruckig_s": tr, "kind": kind})
        progress.update(c + 1)
    progress.close()
    # each binding's floor: a case already at its target (at rest)
    lim, start, _, _ = cases.draw()
    rest = np.column_stack([start[:, 0], np.zeros(args.dofs), np.zeros(args.dofs)])
    floor = {}
    for side in sides:
        side.prepare(lim, rest, rest)
        floor[side.name] = float(np.median([time_calls(side, clock, args.calls) for _ in range(200)]))
    report["machine"]["load_average_after"] = common.machine()["load_average"]
    report["comparison"] = compare
    report["largest_relative_difference"] = largest
    report["examples"] = examples
    report["libraries"] = {}
    for side in sides:
        st = stats[side.name]
        t = np.array(st["times"]) * 1e-3
        report["libraries"][side.name] = {
            "failed": st["failed"], "infeasible": st["infeasible"],
            "worst_limit_excess": st["worst_excess"], "worst_end_error": st["worst_end"],
            "mean_us": float(t.mean()), "median_us": float(np.median(t)),
            "p99_us": float(np.percentile(t, 99)), "max_us": float(t.max()),
            "floor_us": floor[side.name] * 1e-3}
    m, r = report["libraries"]["mjarm"], report["libraries"]["ruckig"]
    report["ratio"] = {"mean": m["mean_us"] / r["mean_us"], "median": m["median_us"] / r["median_us"]}
    common.emit(args, report, format_text(report))


def format_text(report):
    parts = [common.header("Ruckig and mjarm's jerk-limited generator side by side", report), ""]
    rows = []
    for kind, label in (("within", "every DoF starts within its limits"),
                        ("beyond", "some DoF starts beyond its limits")):
        c = report["comparison"][kind]
        rows.append([label, c["cases"], c["equal"],
                     f"{c['mjarm_shorter'][0]} ({c['mjarm_shorter'][1]} infeasible)",
                     f"{c['ruckig_shorter'][0]} ({c['ruckig_shorter'][1]} infeasible)"])
    parts.append(common.table(["cases", "count", "equal durations", "mjarm shorter",
                               "Ruckig shorter"], rows))
    big = report["largest_relative_difference"]
    parts += ["", f"Largest relative difference where mjarm was shorter: "
              f"{big['mjarm_shorter']:.2e}; where Ruckig was shorter: {big['ruckig_shorter']:.2e}.",
              "", "Per library:", ""]
    rows = []
    for name, label in (("mjarm", "mjarm"), ("ruckig", "Ruckig")):
        x = report["libraries"][name]
        rows.append([label, x["failed"], x["infeasible"], f"{x['worst_limit_excess']:.1e}",
                     f"{x['worst_end_error']:.1e}", f"{x['mean_us']:.2f}", f"{x['median_us']:.2f}",
                     f"{x['p99_us']:.2f}", f"{x['floor_us']:.2f}"])
    parts.append(common.table(["library", "failed", "infeasible", "worst limit excess",
                               "worst end error", "mean [µs]", "median [µs]", "p99 [µs]",
                               "at target [µs]"], rows))
    r = report["ratio"]
    parts += ["", f"mjarm / Ruckig: {r['mean']:.2f} (mean), {r['median']:.2f} (median)."]
    return "\n".join(parts)


if __name__ == "__main__":
    main()
