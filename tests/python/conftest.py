"""Shared fixtures of the Python suite: the bundled models it uses, loaded once."""
import os

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
