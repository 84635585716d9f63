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


def runs_beside(call, most=20):
    """Calls call() on another thread, again until this thread has run Python code while the
    other was inside a call (at most `most` calls); returns (whether it did, the last call's
    result). The interpreter's switch interval is set far beyond the calls, so the other thread
    keeps the GIL while it runs Python code: this thread can run during a call only if the call
    released the GIL. Then it runs as soon as the OS gives it a core, and every further call is
    another chance, however fast the machine or busy its cores; with the GIL held it cannot run
    at all, whatever the number of calls. So the verdict does not depend on how long a call
    takes (the earlier form called once and needed the OS to schedule this thread within it)."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        inside, seen, done, result = threading.Event(), threading.Event(), threading.Event(), []

        def worker():
            inside.set()
            for _ in range(most):
                result[:] = [call()]
                if seen.is_set():  # this thread ran during that call: no need for another
                    break
            done.set()

        thread = threading.Thread(target=worker)
        thread.start()  # returns once the worker released the GIL: in a call, or at its end
        inside.wait()
        ran_during_call = not done.is_set()
        seen.set()
        thread.join()
    finally:
        sys.setswitchinterval(old)
    return ran_during_call, result[0]
