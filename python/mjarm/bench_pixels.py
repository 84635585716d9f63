"""Pictures as observations, their rate: ``python3 -m mjarm.bench_pixels [--steps N] [--json]``.

Protocol: the reach task with the ``ee_pose_deltas`` action space, observing ``pixels:free`` (the
free camera framing the model) and ``joint_positions``, at 84×84 and 480×480, beside the same
environment without the picture; N seeded random steps each (episode resets included), one
after the other in one process. Prints the pictures per second (steps per second with a picture
each), the time a picture adds to a step, and the megapixels per second. Rendering is headless
(EGL on Mesa: llvmpipe on a machine without a GPU driver).
"""
import argparse
import json
import sys

import numpy as np

import mjarm
from mjarm.bench_task import time_per_step


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m mjarm.bench_pixels", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=300, help="steps per size, 10..10^6")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    if not 10 <= args.steps <= 10**6:
        parser.error("--steps must be in 10..10^6")
    base = mjarm.Environment("reach", observations=["joint_positions"])
    spec = base.action_spec()
    actions = np.random.default_rng(0).uniform(spec.minimum, spec.maximum,
                                               (args.steps, spec.minimum.size))
    without = time_per_step(base, actions)
    figures = {"steps": args.steps, "step_without_picture_ms": without * 1e3, "sizes": []}
    for size in (84, 480):
        env = mjarm.Environment("reach", observations=["pixels:free", "joint_positions"],
                                pixels_width=size, pixels_height=size)
        with_picture = time_per_step(env, actions)
        figures["sizes"].append({
            "size": size, "pictures_per_second": 1.0 / with_picture,
            "picture_ms": (with_picture - without) * 1e3,
            "megapixels_per_second": size * size / with_picture / 1e6})
        if not args.json and sys.stderr.isatty():
            print(f"{size}x{size} done", file=sys.stderr)
    if args.json:
        print(json.dumps(figures))
    else:
        print(f"reach, {args.steps} steps per size; a step without a picture "
              f"{without * 1e3:.3f} ms")
        for f in figures["sizes"]:
            print(f"  {f['size']}x{f['size']}: {f['pictures_per_second']:8.1f} pictures/s, "
                  f"{f['picture_ms']:7.3f} ms a picture, "
                  f"{f['megapixels_per_second']:6.2f} Mpixel/s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
