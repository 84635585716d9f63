"""Run by wheel_check.py with the fresh environment's interpreter, outside the source tree:
the installed mjarm loads a bundled model from its own package, solves an IK, shares its MuJoCo
with `import mujoco`, and the process maps one libmujoco, the environment's.

Usage: installed_check.py MJARM_VERSION MUJOCO_VERSION
"""
import importlib.metadata
import os
import sys
import sysconfig

import numpy as np

import mjarm
import mujoco

version, mujoco_version = sys.argv[1], sys.argv[2]
site = os.path.realpath(sysconfig.get_paths()["platlib"])
package = os.path.join(site, "mjarm")


def expect(condition, what):
    if not condition:
        sys.exit(f"installed_check: {what}")


expect(os.path.realpath(mjarm.__file__).startswith(package + os.sep),
       f"mjarm imports from the environment ({mjarm.__file__})")
expect(importlib.metadata.version("mjarm") == version,
       f"the installed distribution is mjarm {version}")
expect(mujoco.__version__ == mujoco_version, f"mujoco is {mujoco_version} ({mujoco.__version__})")

# the bundled models are the package's
models = os.path.join(package, "models")
expect(str(mjarm.Robot.models_dir()) == models, f"models_dir {mjarm.Robot.models_dir()} is {models}")
expect("panda" in mjarm.Robot.bundled_names(), "panda is a bundled model")

# an IK solve on a bundled arm: from the chain's centre to the pose of another configuration
robot = mjarm.Robot.bundled("panda")
chain = mjarm.Chain(robot, "attachment_site")
kinematics = mjarm.ChainKinematics(chain)
q_target = chain.center() + 0.3
X_WT = kinematics.update(q_target)
result = mjarm.PoseIk(chain).solve(X_WT, chain.center())
expect(result.ok(), f"the IK converges: {result}")
X_WE = kinematics.update(result.q)
expect(np.linalg.norm(X_WE.p - X_WT.p) < 1e-4, f"the IK reaches the target: {X_WE.p} vs {X_WT.p}")

# mujoco reads the same model file and agrees on its size
model = mujoco.MjModel.from_xml_path(os.path.join(models, "panda.xml"))
expect(model.nq == robot.nq, f"mujoco and mjarm agree on nq ({model.nq}, {robot.nq})")

# one libmujoco in the process: the environment's, which both packages use
with open("/proc/self/maps") as maps:
    loaded = {line.split(maxsplit=5)[5].strip() for line in maps
              if len(line.split(maxsplit=5)) == 6 and "libmujoco" in line}
expected = os.path.join(site, "mujoco", f"libmujoco.so.{mujoco_version}")
expect({os.path.realpath(p) for p in loaded} == {expected},
       f"one libmujoco, {expected}, is mapped: {sorted(loaded)}")
print(f"installed_check: mjarm {version} with MuJoCo {mujoco_version} from {site}: IK solved in "
      f"{result.iterations} iterations, one libmujoco")
