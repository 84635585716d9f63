"""Writes tests/ctest_costs.txt, the test timings a fresh build's CTest starts from.

CTest runs the longest tests first when it knows their times (Testing/Temporary/CTestCostData.txt,
written after each run); a fresh build has none and runs the suite in declaration order, so a long
test that comes late leaves one core busy at the end. tests/CMakeLists.txt copies this file into a
build that has no timings of its own. Refresh it from a build that has run the suite:

    python3 scripts/ctest_costs.py build-test

It keeps the tests of the current suite that took at least MIN_SECONDS (the rest run last, in
declaration order, and fill the gaps), without those whose COST property tests/CMakeLists.txt sets.
"""

import pathlib
import re
import subprocess
import sys

MIN_SECONDS = 0.3


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: scripts/ctest_costs.py BUILD_DIR")
    build = pathlib.Path(sys.argv[1])
    data = build / "Testing" / "Temporary" / "CTestCostData.txt"
    if not data.is_file():
        sys.exit(f"{data}: no timings yet (run the suite in {build} first)")
    listing = subprocess.run(["ctest", "-N"], cwd=build, text=True, capture_output=True, check=True)
    current = set(re.findall(r"Test +#\d+: (\S+)", listing.stdout))
    source = pathlib.Path(__file__).resolve().parent.parent
    fixed = set(re.findall(r"set_tests_properties\((\w+)[^)]*COST",
                           (source / "tests" / "CMakeLists.txt").read_text(), re.S))
    costs = []
    for line in data.read_text().splitlines():
        if line.startswith("---"):
            break  # the failed tests of the last run follow
        name, runs, seconds = line.rsplit(maxsplit=2)
        # a parameterized test's name holds its parameter's bytes (they change between builds)
        if " " in name:
            continue
        if name in current and name not in fixed and float(seconds) >= MIN_SECONDS:
            costs.append((float(seconds), name))
    costs.sort(reverse=True)
    out = source / "tests" / "ctest_costs.txt"
    out.write_text("".join(f"{name} 1 {seconds:.2f}\n" for seconds, name in costs))
    print(f"{out}: {len(costs)} of {len(current)} tests, {sum(s for s, _ in costs):.0f} s")


if __name__ == "__main__":
    main()
