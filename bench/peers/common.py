"""What the peer benchmarks (bench/peers/*_side_by_side.py) share: the command line's common
options, versions, the machine's state, progress on a terminal and Markdown tables."""
import argparse
import importlib.metadata
import json
import os
import subprocess
import sys
import time

import mjarm

CLOCKS = {
    # the calling thread's CPU time: time the thread waits for a core (a shared machine) is not
    # counted, on either side
    "cpu": time.thread_time_ns,
    "wall": time.perf_counter_ns,
}


def parser(description):
    """An argument parser with the options every peer benchmark takes."""
    p = argparse.ArgumentParser(description=description,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--seed", type=int, default=0, help="seed of the random cases (default 0)")
    p.add_argument("--clock", choices=sorted(CLOCKS), default="cpu",
                   help="clock of the per-call times: thread CPU time (default) or wall time")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (protocol, versions, figures) instead of tables")
    return p


def positive(kind):
    def check(text):
        value = kind(text)
        if value <= 0:
            raise argparse.ArgumentTypeError(f"expected a positive number, got {text}")
        return value
    return check


def versions(*distributions):
    """mjarm's version and commit, MuJoCo's, and each named PyPI distribution's."""
    out = {"mjarm": mjarm.__version__, "mujoco": importlib.metadata.version("mujoco")}
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, cwd=os.path.dirname(os.path.abspath(__file__)))
        if commit.returncode == 0:
            out["mjarm"] += f" ({commit.stdout.strip()})"
    except OSError:
        pass
    for name in distributions:
        out[name] = importlib.metadata.version(name)
    return out


def machine():
    """The state the figures were measured in."""
    return {"utc": time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime()),
            "load_average": [round(x, 2) for x in os.getloadavg()], "cpus": os.cpu_count()}


class Progress:
    """`label k/n` on stderr, rewritten in place, only when stderr is a terminal (quiet when the
    output goes to a pipe or a file)."""

    def __init__(self, label, total):
        self.label, self.total = label, total
        self.enabled = sys.stderr.isatty()
        self.last = 0.0

    def update(self, done):
        now = time.monotonic()
        if self.enabled and (now - self.last > 0.2 or done == self.total):
            self.last = now
            sys.stderr.write(f"\r{self.label} {done}/{self.total}")
            sys.stderr.flush()

    def close(self):
        if self.enabled:
            sys.stderr.write("\r\x1b[K")
            sys.stderr.flush()


def table(headers, rows):
    """A Markdown table."""
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def emit(args, report, text):
    """The report as JSON (--json) or the text."""
    try:
        if args.json:
            json.dump(report, sys.stdout, indent=2)
            sys.stdout.write("\n")
        else:
            print(text)
        sys.stdout.flush()
    except BrokenPipeError:  # the reader stopped early (| head): not an error of the benchmark
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())


def header(title, report):
    """The lines that open every text report: versions, machine, protocol."""
    v = ", ".join(f"{k} {x}" for k, x in report["versions"].items())
    m = report["machine"]
    load = " / ".join(f"{x:.2f}" for x in m["load_average"])
    after = m.get("load_average_after")
    after = "" if after is None else f" (after: {' / '.join(f'{x:.2f}' for x in after)})"
    lines = [f"# {title}", "", f"Versions: {v}.",
             f"Measured {m['utc']} UTC, load average {load} (1 / 5 / 15 min){after} on "
             f"{m['cpus']} CPUs.", "", "Protocol:"]
    lines += [f"- {line}" for line in report["protocol"]]
    return "\n".join(lines)
