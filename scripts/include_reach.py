#!/usr/bin/env python3
"""How many translation units of a build reach a header, directly or through other headers.

Reads a CMake build's `compile_commands.json`, runs each unit's own compile command with `-M`
instead of `-c -o` (the preprocessor only: it lists every file the unit includes, as the compiler
resolves it) and counts, for each header asked about, the units whose list holds it. A header is
matched by the end of its path (`Eigen/Cholesky` matches `/usr/include/eigen3/Eigen/Cholesky`).

    python3 scripts/include_reach.py build                      # the heavy Eigen decompositions
    python3 scripts/include_reach.py build --header Eigen/SVD --list
    python3 scripts/include_reach.py build --json > reach.json

The units are grouped by where their source lies in the source tree (`src/control`, `tests`,
`app`, `python`, ...; a unity unit by the folder of its first file). Standard library only.
Exit status 0, or 1 when a unit's command failed (named on stderr), 2 for bad arguments.
"""

import argparse
import concurrent.futures
import json
import os
import re
import shlex
import subprocess
import sys

DEFAULT_HEADERS = ["Eigen/Cholesky", "Eigen/Eigenvalues", "Eigen/SVD", "Eigen/LU", "Eigen/QR",
                   "Eigen/Geometry"]
# arguments that write an object or a dependency file (dropped, with their value when they take one)
DROP_WITH_VALUE = {"-o", "-MF", "-MT", "-MQ"}
DROP_ALONE = {"-c", "-MD", "-MMD"}
LAUNCHERS = {"ccache", "sccache", "distcc"}


def read_units(build_dir):
    path = os.path.join(build_dir, "compile_commands.json")
    try:
        with open(path, encoding="utf-8") as f:
            entries = json.load(f)
    except FileNotFoundError:
        raise SystemExit(f"include_reach: no {path}; configure the build with CMake first "
                         "(CMAKE_EXPORT_COMPILE_COMMANDS is on in mjarm)")
    except json.JSONDecodeError as e:
        raise SystemExit(f"include_reach: {path} is not JSON: {e}")
    if not isinstance(entries, list):
        raise SystemExit(f"include_reach: {path} is not a list of compile commands")
    # one unit per command: a file compiled into two targets is two units
    units = []
    for entry in entries:
        args = entry.get("arguments") or shlex.split(entry["command"])
        units.append((os.path.normpath(os.path.join(entry["directory"], entry["file"])),
                      entry["directory"], args))
    return units


def dependency_command(args):
    while args and os.path.basename(args[0]) in LAUNCHERS:
        args = args[1:]
    out, skip = [], False
    for arg in args:
        if skip:
            skip = False
        elif arg in DROP_WITH_VALUE:
            skip = True
        elif arg in DROP_ALONE or any(arg.startswith(p) and len(arg) > len(p)
                                      for p in DROP_WITH_VALUE):
            continue
        else:
            out.append(arg)
    return out + ["-M"]


def dependencies(directory, args):
    run = subprocess.run(dependency_command(args), cwd=directory, capture_output=True, text=True)
    if run.returncode != 0:
        return None, run.stderr.strip().splitlines()[-1:] or ["failed"]
    text = run.stdout.replace("\\\n", " ")
    files = text.split(":", 1)[1].split() if ":" in text else []
    return [os.path.normpath(os.path.join(directory, f)) for f in files], None


def unity_first_file(path):
    """The first file a CMake unity source includes, else the path itself."""
    if "/Unity/" not in path:
        return path
    try:
        with open(path, encoding="utf-8") as f:
            for line in f:
                m = re.match(r'\s*#include\s+"([^"]+)"', line)
                if m:
                    return m.group(1)
    except OSError:
        pass
    return path


def group_of(path, source_dir):
    rel = os.path.relpath(unity_first_file(path), source_dir)
    if rel.startswith(".."):
        return "(outside the source tree)"
    parts = rel.split(os.sep)
    if parts[0] == "src" and len(parts) > 2:
        return "src/" + parts[1]
    return parts[0] if len(parts) > 1 else "(top level)"


def main():
    parser = argparse.ArgumentParser(
        description="Count the translation units of a CMake build that reach each header "
                    "(through compile_commands.json and the compiler's -M).")
    parser.add_argument("build_dir", help="the build folder holding compile_commands.json")
    parser.add_argument("--header", action="append", metavar="PATH",
                        help="a header to count, matched by the end of its path (repeatable; "
                             "default: " + ", ".join(DEFAULT_HEADERS) + ")")
    parser.add_argument("--source-dir", default=os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))), help="the source tree the groups are relative to "
                                          "(default: this script's repository)")
    parser.add_argument("--jobs", "-j", type=int, default=os.cpu_count() or 1,
                        help="compiler processes at once (default: the number of cores)")
    parser.add_argument("--list", action="store_true",
                        help="also list the units that reach each header")
    parser.add_argument("--json", action="store_true",
                        help="print one JSON object: units, and per header its count, its "
                             "count per group and the units")
    options = parser.parse_args()
    headers = options.header or DEFAULT_HEADERS
    if options.jobs < 1:
        parser.error(f"--jobs must be at least 1, got {options.jobs}")

    units = read_units(options.build_dir)
    deps, failed = {}, {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=options.jobs) as pool:
        futures = {pool.submit(dependencies, d, a): i for i, (_, d, a) in enumerate(units)}
        for future in concurrent.futures.as_completed(futures):
            files, error = future.result()
            if files is None:
                failed[futures[future]] = error[0]
            else:
                deps[futures[future]] = files

    names = {i: units[i][0] for i in deps}
    groups = {i: group_of(names[i], options.source_dir) for i in deps}
    group_sizes = {}
    for g in groups.values():
        group_sizes[g] = group_sizes.get(g, 0) + 1
    report = {"build_dir": os.path.abspath(options.build_dir), "units": len(deps),
              "units_per_group": dict(sorted(group_sizes.items())),
              "failed": sorted(units[i][0] + ": " + e for i, e in failed.items()),
              "headers": {}}
    for header in headers:
        suffix = "/" + header.strip("/")
        reaching = [i for i, files in deps.items() if any(d.endswith(suffix) for d in files)]
        per_group = {}
        for i in reaching:
            per_group[groups[i]] = per_group.get(groups[i], 0) + 1
        report["headers"][header] = {"units": len(reaching),
                                     "per_group": dict(sorted(per_group.items())),
                                     "reaching": sorted(names[i] for i in reaching)}

    if options.json:
        json.dump(report, sys.stdout, indent=1)
        print()
    else:
        print(f"{report['units']} translation units in {report['build_dir']}")
        width = max(len(h) for h in headers)
        for header, r in report["headers"].items():
            groups_text = ", ".join(f"{g} {n}" for g, n in
                                    sorted(r["per_group"].items(), key=lambda x: (-x[1], x[0])))
            print(f"{header:<{width}}  {r['units']:4d}  ({groups_text})" if groups_text else
                  f"{header:<{width}}  {r['units']:4d}")
            if options.list:
                for f in r["reaching"]:
                    print(f"    {os.path.relpath(f, options.source_dir)}")
    for line in report["failed"]:
        print(f"include_reach: the compiler failed on {line}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
