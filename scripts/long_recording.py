#!/usr/bin/env python3
"""Makes a long recording out of a short one, for measuring `mjarm replay-html` on it.

    python3 scripts/long_recording.py SRC DST --rows N

DST gets SRC's summary.json (its end_time and duration made to match), events.csv and
model.mjb, and a state.csv of N rows: SRC's state rows over and over, their time continued (each
repetition starts one step after the last ended), and a task.csv lengthened in the same proportion.
The motion jumps back to the start at each repetition; the replay does not mind. Rows are written
as they are made (bounded memory); 10^7 rows of a bundled arm are about 4 GB (docs/replay.md).
"""

import argparse
import json
import os
import shutil
import sys


def read_rows(path):
    with open(path, encoding="utf-8") as f:
        header = f.readline()
        rows = []
        for line in f:
            if line.strip():
                t, rest = line.rstrip("\n").split(",", 1)
                rows.append((float(t), rest))
    if len(rows) < 2:
        sys.exit(f"{path}: needs at least two rows")
    return header, rows


def lengthen(src, dst, rows_wanted):
    """Writes rows_wanted rows of src's rows repeated with their time continued; returns the end."""
    header, rows = read_rows(src)
    t0 = rows[0][0]
    step = rows[1][0] - rows[0][0]
    period = rows[-1][0] - t0 + step
    written = 0
    t = t0
    with open(dst, "w", encoding="utf-8", buffering=1 << 22) as out:
        out.write(header)
        repetition = 0
        while written < rows_wanted:
            shift = repetition * period
            lines = []
            for t_row, rest in rows[: rows_wanted - written]:
                t = t_row + shift
                lines.append(f"{t:.9g},{rest}\n")
            out.write("".join(lines))
            written += len(lines)
            repetition += 1
    return t


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("src", help="a recording folder (mjarm run ... --record SRC)")
    parser.add_argument("dst", help="the folder to write (created; must not exist)")
    parser.add_argument("--rows", type=int, required=True, help="state.csv rows to write")
    args = parser.parse_args()
    if args.rows < 2:
        sys.exit("--rows: at least 2")
    if os.path.exists(args.dst):
        sys.exit(f"{args.dst} exists: name a new folder")
    os.makedirs(args.dst)
    _, state = read_rows(os.path.join(args.src, "state.csv"))
    _, task = read_rows(os.path.join(args.src, "task.csv"))
    task_rows = max(2, round(args.rows * len(task) / len(state)))
    end = lengthen(os.path.join(args.src, "state.csv"), os.path.join(args.dst, "state.csv"),
                   args.rows)
    lengthen(os.path.join(args.src, "task.csv"), os.path.join(args.dst, "task.csv"), task_rows)
    for name in ("events.csv", "model.mjb"):
        if os.path.exists(os.path.join(args.src, name)):
            shutil.copyfile(os.path.join(args.src, name), os.path.join(args.dst, name))
    with open(os.path.join(args.src, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    if "end_time" in summary:
        summary["end_time"] = end
    if "duration" in summary and "start_time" in summary:
        summary["duration"] = end - summary["start_time"]
    with open(os.path.join(args.dst, "summary.json"), "w", encoding="utf-8") as f:
        json.dump(summary, f, indent=2)
    print(f"{args.dst}: {args.rows} state rows, {task_rows} task rows, t up to {end:.6g} s")


if __name__ == "__main__":
    main()
