"""Conformance of every mjarm environment to the two interfaces it is offered through: dm_env's
contract (``dm_env.test_utils.EnvironmentTestMixin`` on ``mjarm.dm_env.DmEnv``) and Gymnasium's
(``gymnasium.utils.env_checker.check_env`` on ``mjarm.gym.GymEnv``), for every task with every
action space. Episodes are 5 steps (time_limit 0.1 s) so that each sequence crosses several
episode ends; then the fixes these checks asked for, each with its own test."""
import itertools
import warnings

import dm_env
import numpy as np
import pytest
from absl.testing import absltest
from dm_env import test_utils
from gymnasium import spaces
from gymnasium.utils.env_checker import check_env

import mjarm
from mjarm.dm_env import DmEnv
from mjarm.gym import GymEnv

ACTION_SPACES = ["joint_torques", "joint_positions", "joint_deltas", "ee_pose_deltas",
                 "ee_velocities"]
CASES = list(itertools.product(mjarm.env_task_names(), ACTION_SPACES))
TIME_LIMIT = 0.1  # 5 control steps of 20 ms


def test_every_task_is_covered():
    # the cases come from the registry: an empty list would check nothing, silently
    assert {"reach", "shelf-pick", "pick-place", "docking"} <= set(mjarm.env_task_names())
    assert len(CASES) == len(mjarm.env_task_names()) * len(ACTION_SPACES)
    assert set(ACTION_SPACES) == {s.name for s in mjarm.ActionSpace.__members__.values()}


# --- dm_env ---------------------------------------------------------------------------------

class _DmEnvConformance(test_utils.EnvironmentTestMixin):
    task = action_space = None

    def make_object_under_test(self):
        return DmEnv(self.task, time_limit=TIME_LIMIT, action_space=self.action_space)

    def make_action_sequence(self):
        # the bounds' corners (what drives an arm into its joint limits) and seeded random actions
        # in between: 24 steps, so every run crosses LAST and the FIRST after it several times
        spec = self.environment.action_spec()
        rng = np.random.default_rng(0)
        for k in range(24):
            if k % 3 == 0:
                yield spec.minimum.copy()
            elif k % 3 == 1:
                yield spec.maximum.copy()
            else:
                yield rng.uniform(spec.minimum, spec.maximum)


# one absltest class per (task, action space): pytest collects them and runs the mixin's tests
for _task, _space in CASES:
    _name = "TestDmEnv_" + _task.replace("-", "_") + "_" + _space
    globals()[_name] = type(_name, (_DmEnvConformance, absltest.TestCase),
                            {"task": _task, "action_space": _space})


def test_dm_env_steps_equal_the_native_environment_and_reset_itself():
    native = mjarm.Environment("reach", time_limit=TIME_LIMIT)
    env = DmEnv("reach", time_limit=TIME_LIMIT)
    assert isinstance(env, dm_env.Environment)
    action = np.full(6, 0.01)
    # a fresh environment: step() is reset() (the action is not used), with the next seed
    first = env.step(action)
    assert first.step_type is dm_env.StepType.FIRST and first.reward is None
    assert np.array_equal(first.observation["ee_pose"], native.reset().observation["ee_pose"])
    steps = [env.step(action) for _ in range(5)]
    ours = [native.step(action) for _ in range(5)]
    assert [s.step_type for s in steps] == [dm_env.StepType.MID] * 4 + [dm_env.StepType.LAST]
    for a, b in zip(steps, ours):
        assert a.reward == b.reward and a.discount == b.discount
        assert all(np.array_equal(a.observation[k], b.observation[k]) for k in b.observation)
    # after LAST, step() starts the next episode (the native environment refuses the step)
    with pytest.raises(mjarm.Error, match="reset"):
        native.step(action)
    again = env.step(action)
    assert again.first() and np.array_equal(again.observation["target"],
                                            native.reset().observation["target"])
    assert env.reset(seed=3).observation["target"].tolist() == \
        native.reset(3).observation["target"].tolist()


def test_dm_env_specs_are_dm_env_specs_with_the_bounds():
    env = DmEnv("pick-place")
    a = env.action_spec()
    assert isinstance(a, dm_env.specs.BoundedArray) and a.shape == (7,) and a.maximum[6] == 1.0
    obs = env.observation_spec()
    assert list(obs) == list(env.env.observation_spec())
    assert type(obs["joint_velocities"]) is dm_env.specs.Array  # no finite bound
    assert isinstance(obs["ee_pose"], dm_env.specs.BoundedArray) and obs["ee_pose"].maximum[3] == 1.0
    with pytest.raises(TypeError):
        DmEnv()


# --- Gymnasium ------------------------------------------------------------------------------

@pytest.mark.parametrize("flatten", [False, True], ids=["dict", "flat"])
@pytest.mark.parametrize("task,action_space", CASES)
def test_gymnasium_check_env(task, action_space, flatten):
    env = GymEnv(task, flatten=flatten, time_limit=TIME_LIMIT, action_space=action_space)
    with warnings.catch_warnings():
        # the checker only warns about an observation outside its space: here that fails
        warnings.filterwarnings("error", message=".*not within the observation space")
        # advice, not conformance: infinite bounds (velocities, forces have none), an action
        # box in physical units rather than [-1, 1], no registered spec to remake the env from
        warnings.filterwarnings("ignore", message=".*(infinity|normalized space|not having a spec)")
        check_env(env)
        # and a longer run at the action bounds' corners, where joints reach their limits
        obs, _ = env.reset(seed=0)
        for k in range(12):
            action = env.action_space.low if k % 2 == 0 else env.action_space.high
            obs, reward, terminated, truncated, _ = env.step(action)
            assert obs in env.observation_space
            if terminated or truncated:
                obs, _ = env.reset()


def test_gym_spaces_are_gymnasium_spaces_in_spec_order():
    env = GymEnv("docking")
    assert isinstance(env.action_space, spaces.Box) and env.action_space.dtype == np.float64
    assert isinstance(env.observation_space, spaces.Dict)
    # gymnasium sorts a plain dict's keys: the adapter keeps the environment's order
    assert list(env.observation_space.keys()) == list(env.env.observation_spec())
    assert list(env.observation_space.keys()) != sorted(env.observation_space.keys())
    obs, _ = env.reset(seed=1)
    assert list(obs) == list(env.observation_space.keys())


def test_joint_positions_past_a_soft_limit_are_within_the_spec():
    # full torques push a joint past its limit (MuJoCo's limits are soft); the observation spec
    # used to claim the limits as bounds, which dm_env's validate() and check_env's space test
    # refused: it is unbounded now
    env = DmEnv("reach", action_space="joint_torques")
    panda = mjarm.Chain(mjarm.Robot.bundled("panda"), "attachment_site")  # the reach task's arm
    lower, upper = panda.lower, panda.upper
    spec = env.observation_spec()["joint_positions"]
    env.reset(seed=1)
    beyond = False
    for _ in range(50):
        ts = env.step(env.action_spec().minimum)
        q = ts.observation["joint_positions"]
        spec.validate(q)
        beyond = beyond or bool(np.any(q < lower) or np.any(q > upper))
        if beyond or ts.last():
            break
    assert beyond
