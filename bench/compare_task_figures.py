#!/usr/bin/env python3
"""Side-by-side task figures of two bench/task_figures.sh folders (e.g. the old and the new
MuJoCo): markdown tables of docs/mujoco.md, or with --json the compared rows as one document."""
import argparse
import json
import os
import sys


def load(folder, name):
    try:
        with open(os.path.join(folder, name + ".json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def mm(x):
    return "—" if x is None else f"{1000 * x:.3f}"


def shelf(old, new):
    a, b = load(old, "shelf_all"), load(new, "shelf_all")
    if not (a and b):
        return []
    return [{"robot": ra["robot"], "controller": ra["controller"],
             "held": [f"{ra['held']}/{ra['runs']}", f"{rb['held']}/{rb['runs']}"],
             "worst_time_to_tolerance_s": [ra["worst_time_to_tolerance"], rb["worst_time_to_tolerance"]],
             "worst_overshoot_m": [ra["worst_overshoot"], rb["worst_overshoot"]],
             "worst_steady_state_max_m": [ra["worst_steady_state_max"], rb["worst_steady_state_max"]]}
            for ra, rb in zip(a["rows"], b["rows"])]


def pick_place(old, new):
    rows = []
    for robot in ["arm6", "panda_hand"]:
        for grasp in ["weld", "friction"]:
            for mode in ["position", "torque"]:
                name = f"pp_{robot}_{grasp}_{mode}"
                a, b = load(old, name), load(new, name)
                if not (a and b):
                    continue
                sa, sb = a["summary"], b["summary"]
                rows.append({
                    "robot": robot, "grasp": grasp, "mode": mode,
                    "success": [f"{sa['successes']}/{sa['trials']}", f"{sb['successes']}/{sb['trials']}"],
                    "failures_new": {k: v for k, v in sb["failures"].items() if v},
                    "placement_mean_max_m": [[s["placement_error"]["mean"], s["placement_error"]["max"]]
                                             if s["placement_error"]["count"] else None for s in (sa, sb)],
                    "cycle_time_mean_s": [sa["cycle_time"]["mean"], sb["cycle_time"]["mean"]],
                    "grasp_force_mean_n": [sa["grasp_force"]["mean"], sb["grasp_force"]["mean"]],
                    "slip_max_m": [sa["max_slip"]["max"], sb["max_slip"]["max"]]})
    return rows


VARIANTS = ["", "_sensorless", "_friction", "_friction_sensorless"]


def docking(old, new, kind):
    rows = []
    for v in VARIANTS:
        a, b = load(old, f"dock_{kind}{v}"), load(new, f"dock_{kind}{v}")
        if not (a and b):
            continue
        for ca, cb in zip(a["controllers"], b["controllers"]):
            row = {"variant": (v.strip("_").replace("_", " ") or "plain"),
                   "controller": ca["controller"], "source": ca["source"]}
            if kind == "grid":
                row.update({"seated": [f"{ca['seated']}/{ca['runs']}", f"{cb['seated']}/{cb['runs']}"],
                            "max_peak_force_n": [ca["max_peak_force"], cb["max_peak_force"]],
                            "max_lateral_m": [ca["max_lateral"], cb["max_lateral"]],
                            "failures_new": cb["failures"]})
            else:
                row.update({"position_rms_m": [ca["total"]["position_rms"], cb["total"]["position_rms"]],
                            "orientation_rms_rad": [ca["total"]["orientation_rms"],
                                                    cb["total"]["orientation_rms"]]})
            rows.append(row)
    return rows


def bimanual(old, new):
    rows = []
    for mode in ["position", "torque"]:
        a, b = load(old, "bimanual_" + mode), load(new, "bimanual_" + mode)
        if a and b:
            rows.append({"mode": mode, "success": [a["success"], b["success"]],
                         "lifted_m": [a["lifted"], b["lifted"]], "sag_m": [a["sag"], b["sag"]],
                         "grasp_force_n": [a["grasp_force"], b["grasp_force"]]})
    return rows


def print_tables(doc):
    print("Shelf pick (100 seeds per robot and controller), old / new")
    print("| robot | controller | held | worst time to 1 mm [s] | worst overshoot [mm] | worst steady-state max [mm] |")
    print("|---|---|---|---|---|---|")
    for r in doc["shelf_pick"]:
        t, o, s = r["worst_time_to_tolerance_s"], r["worst_overshoot_m"], r["worst_steady_state_max_m"]
        print(f"| {r['robot']} | {r['controller']} | {' / '.join(r['held'])} | {t[0]:.3f} / {t[1]:.3f} | "
              f"{mm(o[0])} / {mm(o[1])} | {mm(s[0])} / {mm(s[1])} |")
    print("\nPick and place (200 trials, seeds 1-200), old / new")
    print("| robot | grasp | mode | success | failures (new) | placement mean, max [mm] | cycle time mean [s] | grasp force mean [N] | slip max [mm] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in doc["pick_place"]:
        pe = " / ".join("—" if p is None else f"{mm(p[0])}, {mm(p[1])}" for p in r["placement_mean_max_m"])
        fails = ", ".join(f"{k} {v}" for k, v in r["failures_new"].items()) or "none"
        c, g, sl = r["cycle_time_mean_s"], r["grasp_force_mean_n"], r["slip_max_m"]
        print(f"| {r['robot']} | {r['grasp']} | {r['mode']} | {' / '.join(r['success'])} | {fails} | {pe} | "
              f"{c[0]:.2f} / {c[1]:.2f} | {g[0]:.2f} / {g[1]:.2f} | {mm(sl[0])} / {mm(sl[1])} |")
    print("\nDocking grid (27 offsets), old / new")
    print("| variant | controller | force source | seated | max peak force [N] | max lateral [mm] | failures (new) |")
    print("|---|---|---|---|---|---|---|")
    for r in doc["docking_grid"]:
        f, l = r["max_peak_force_n"], r["max_lateral_m"]
        fails = ", ".join(f"{k} {v}" for k, v in r["failures_new"].items()) or "none"
        print(f"| {r['variant']} | {r['controller']} | {r['source']} | {' / '.join(r['seated'])} | "
              f"{f[0]:.1f} / {f[1]:.1f} | {mm(l[0])} / {mm(l[1])} | {fails} |")
    print("\nDocking tracking gate (circle and figure eight), old / new")
    print("| variant | controller | force source | position rms [mm] | orientation rms [mrad] |")
    print("|---|---|---|---|---|")
    for r in doc["docking_gate"]:
        p, o = r["position_rms_m"], r["orientation_rms_rad"]
        print(f"| {r['variant']} | {r['controller']} | {r['source']} | {mm(p[0])} / {mm(p[1])} | "
              f"{1000 * o[0]:.3f} / {1000 * o[1]:.3f} |")
    print("\nBimanual lift, old / new")
    print("| mode | success | lifted [m] | sag [mm] | grasp force left, right [N] |")
    print("|---|---|---|---|---|")
    for r in doc["bimanual"]:
        l, s, g = r["lifted_m"], r["sag_m"], r["grasp_force_n"]
        print(f"| {r['mode']} | {r['success'][0]} / {r['success'][1]} | {l[0]:.4f} / {l[1]:.4f} | "
              f"{mm(s[0])} / {mm(s[1])} | {g[0][0]:.1f}, {g[0][1]:.1f} / {g[1][0]:.1f}, {g[1][1]:.1f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("old", help="folder written by bench/task_figures.sh (e.g. the old engine)")
    parser.add_argument("new", help="folder written by bench/task_figures.sh (e.g. the new engine)")
    parser.add_argument("--json", action="store_true", help="print the compared rows as JSON")
    args = parser.parse_args()
    for folder in (args.old, args.new):
        if not os.path.isdir(folder):
            sys.exit(f"compare_task_figures: no folder {folder}")
    doc = {"old": args.old, "new": args.new, "shelf_pick": shelf(args.old, args.new),
           "pick_place": pick_place(args.old, args.new),
           "docking_grid": docking(args.old, args.new, "grid"),
           "docking_gate": docking(args.old, args.new, "gate"),
           "bimanual": bimanual(args.old, args.new)}
    if not any(doc[k] for k in ("shelf_pick", "pick_place", "docking_grid", "docking_gate", "bimanual")):
        sys.exit("compare_task_figures: the two folders have no figures in common")
    if args.json:
        json.dump(doc, sys.stdout, indent=2)
        print()
    else:
        print_tables(doc)


if __name__ == "__main__":
    main()
