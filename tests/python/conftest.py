"""Shared fixtures of the Python suite: the bundled models it uses, loaded once."""
import os
import sys
import threading

import numpy as np
import pytest

import mjarm


@pytest.fixture(scope="session")
def panda():
    return mjarm.Robot.bundled("panda")


@pytest.fixture(scope="session")
def panda_torque():
    return mjarm.Robot.bundled("panda_torque")


@pytest.fixture(scope="session")
def planar2_torque():
    return mjarm.Robot.bundled("planar2_torque")


@pytest.fixture()
def panda_chain(panda):
    return mjarm.Chain(panda, "attachment_site")


@pytest.fixture(scope="session")
def source_dir():
    return os.environ.get("MJARM_SOURCE_DIR",
                          os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))


def home(robot, chain):
    """The chain's joint values at the keyframe 'home'."""
    return chain.gather(robot.keyframe_qpos("home"))


def rng(seed):
    return np.random.default_rng(seed)


def runs_beside(call):
    """Calls call() on another thread; returns (whether this thread ran Python code while the
    other was inside call(), its result). The interpreter's switch interval is set far beyond the
    call, so the other thread keeps the GIL while it runs Python code: this thread can run during
    the call only if the call released the GIL. One turn is enough (not a count of loop turns,
    which depends on the machine's speed); the call should last long enough for the OS to give
    this thread a core once (a tenth of a second: a scheduler slice is a few milliseconds)."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        inside, done, result = threading.Event(), threading.Event(), []

        def worker():
            inside.set()
            result.append(call())
            done.set()

        thread = threading.Thread(target=worker)
        thread.start()  # returns once the worker released the GIL: in the call, or at its end
        inside.wait()
        ran_during_call = not done.is_set()
        thread.join()
    finally:
        sys.setswitchinterval(old)
    return ran_during_call, result[0]
