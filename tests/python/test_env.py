"""The environments from Python: dm_env's TimeStep semantics and specs, determinism with seeds,
time steps that own their observations, the vectorized form, bad input, and the GIL released
while stepping (the speed-up that buys two Python threads is a figure of `python3 -m
mjarm.bench`)."""
import gc
import threading
import time

import numpy as np
import pytest

import mjarm
from conftest import runs_beside


def reach(**overrides):
    return mjarm.Environment("reach", **overrides)


def toward_target(ts, gain=0.3):
    """ee_pose_deltas: gain × the offset to the target, no rotation (the reach test's policy)."""
    action = np.zeros(6)
    action[:3] = gain * ts.observation["target_offset"]
    return action


def test_time_step_first_mid_last_on_truncation():
    env = reach(time_limit=0.1)  # 5 steps of 20 ms
    ts = env.reset(3)
    assert ts.step_type == mjarm.StepType.FIRST and ts.first() and not ts.mid() and not ts.last()
    assert ts.reward is None and ts.discount is None and ts.end == mjarm.EpisodeEnd.running
    types = []
    while not ts.last():
        ts = env.step(np.zeros(6))
        types.append(ts.step_type)
        assert isinstance(ts.reward, float) and ts.reward < 0.0  # -distance
    assert types == [mjarm.StepType.MID] * 4 + [mjarm.StepType.LAST]
    # the time limit is a truncation: discount 1, not a terminal state
    assert ts.discount == 1.0 and ts.end == mjarm.EpisodeEnd.truncated
    assert env.steps == env.step_limit == 5 and env.end == mjarm.EpisodeEnd.truncated
    step_type, reward, discount, observation = ts  # unpacks like dm_env's namedtuple
    assert step_type == mjarm.StepType.LAST and discount == 1.0 and observation is ts.observation
    assert int(mjarm.StepType.FIRST) == 0 and int(mjarm.StepType.MID) == 1 and int(mjarm.StepType.LAST) == 2
    assert mjarm.StepType.LAST.last() and mjarm.StepType.FIRST.first() and mjarm.StepType.MID.mid()


def test_termination_has_discount_zero():
    env = reach(time_limit=3.0)
    ts = env.reset(7)
    while not ts.last():
        ts = env.step(toward_target(ts))
    assert ts.end == mjarm.EpisodeEnd.terminated and ts.discount == 0.0
    assert env.steps < env.step_limit
    assert np.linalg.norm(ts.observation["target_offset"]) <= 0.01  # the reach rule: within 1 cm


def test_specs_follow_dm_env():
    env = reach()
    a = env.action_spec()
    assert a.name == "action" and a.shape == (6,) and a.dtype == np.float64 and a.bounded()
    assert np.allclose(a.maximum, [0.02] * 3 + [0.1] * 3) and np.allclose(a.minimum, -a.maximum)
    value = np.full(6, 0.01)
    assert a.validate(value) is value
    with pytest.raises(ValueError, match=r"expected shape \(6,\), got \(3,\)"):
        a.validate(np.zeros(3))
    with pytest.raises(ValueError, match="expected dtype float64, got float32"):
        a.validate(np.zeros(6, dtype=np.float32))
    with pytest.raises(ValueError, match=r"action\[3\] = 0\.5.* outside"):
        a.validate(np.array([0, 0, 0, 0.5, 0, 0.0]))
    # a huge value in its shortest form, the bounds as typed (issue 29: 309 digits before)
    with pytest.raises(ValueError, match=r"^action\[0\] = 1e\+308 is outside \[-0\.02, 0\.02\]$"):
        a.validate(np.array([1e308, 0, 0, 0, 0, 0.0]))
    assert np.array_equal(a.generate_value(), a.minimum)  # BoundedArray: the minimum
    specs = env.observation_spec()
    ts = env.reset(1)
    assert list(specs) == list(ts.observation)  # same names, same order
    for name, spec in specs.items():
        assert spec.name == name and ts.observation[name].shape == spec.shape
        assert ts.observation[name].dtype == np.float64
    assert np.all(np.isinf(specs["joint_velocities"].minimum))
    assert np.array_equal(specs["joint_velocities"].generate_value(), np.zeros(7))  # Array: zeros
    specs["joint_positions"].validate(ts.observation["joint_positions"])  # home is within limits
    assert sum(s.size for s in specs.values()) == ts.values.shape[0]
    r, d = env.reward_spec(), env.discount_spec()
    assert r.shape == () and d.shape == () and d.minimum == 0.0 and d.maximum == 1.0
    assert d.validate(np.float64(1.0)) == 1.0
    with pytest.raises(ValueError):
        d.validate(np.float64(1.5))
    spec = mjarm.ArraySpec("x", [2, 3], None, np.ones(6))
    assert spec.shape == (2, 3) and spec.maximum.shape == (2, 3)
    assert np.array_equal(spec.generate_value(), np.ones((2, 3)))
    with pytest.raises(mjarm.Error):
        mjarm.ArraySpec("x", [2], [1.0, 1.0], [0.0, 0.0])  # minimum > maximum
    assert "target" in mjarm.env_observations("reach") and "reach" in mjarm.env_task_names()


def trace(env, seed, steps, action_seed):
    rng = np.random.default_rng(action_seed)
    spec = env.action_spec()
    out = [env.reset(seed).values.tobytes()]
    for _ in range(steps):
        ts = env.step(rng.uniform(spec.minimum, spec.maximum))
        out.append(ts.values.tobytes() + np.float64(ts.reward).tobytes())
    return out


def test_same_seed_and_actions_same_observations_bit_for_bit():
    a, b = reach(), reach()
    first = trace(a, 11, 20, 5)
    assert trace(b, 11, 20, 5) == first  # a fresh environment
    trace(b, 12, 7, 6)
    assert trace(b, 11, 20, 5) == first  # one that ran another episode before
    assert trace(a, 12, 20, 5) != first  # another seed, another episode
    # reset() without a seed follows EnvironmentOptions.seed
    c, d = reach(seed=4), reach(seed=4)
    assert c.reset().values.tobytes() == d.reset().values.tobytes()
    assert c.episode_seed == d.episode_seed


def test_time_steps_own_their_observations():
    env = reach()
    first = env.reset(2)
    obs = first.observation
    kept = {k: v.copy() for k, v in obs.items()}
    assert first.observation is obs  # built once per time step
    for name in obs:  # the dict's arrays are views of the time step's one copy
        assert np.shares_memory(obs[name], first.values)
    ts = env.step(np.full(6, 0.02))
    ts = env.step(np.full(6, 0.02))
    assert not np.shares_memory(ts.values, first.values)
    for name in obs:  # the next steps changed nothing in the time step kept
        assert np.array_equal(obs[name], kept[name])
    assert not np.array_equal(ts.observation["ee_pose"], kept["ee_pose"])
    # the copies outlive the environment (ASan checks every read)
    values = ts.values
    joint_positions = ts.observation["joint_positions"]
    del env, ts, first
    gc.collect()
    assert values.sum() == values.sum() and joint_positions.shape == (7,)
    # the arrays are the time step's own: writing one changes no other time step
    joint_positions[:] = 0.0
    assert np.all(obs["joint_positions"] == kept["joint_positions"])


def test_clipping_is_counted_or_refused():
    env = reach()
    env.reset(0)
    env.step(np.array([1.0, 0, 0, 0, 0, -1.0]))  # two values out of bounds
    env.step(np.zeros(6))
    assert env.episode_clips.steps == 1 and env.episode_clips.values == 2
    env.reset(0)
    assert env.episode_clips.steps == 0 and env.total_clips.values == 2
    strict = reach(refuse_out_of_bounds=True)
    strict.reset(0)
    with pytest.raises(mjarm.Error, match=r"action\[0\]"):
        strict.step(np.array([1.0, 0, 0, 0, 0, 0]))


def test_bad_input():
    env = reach(time_limit=0.04)
    with pytest.raises(mjarm.Error, match="reset"):
        env.step(np.zeros(6))  # before reset
    env.reset(0)
    with pytest.raises(ValueError, match=r"action: expected shape \(6,\), got \(3,\)"):
        env.step(np.zeros(3))
    with pytest.raises(ValueError, match=r"action: expected shape \(6,\), got \(1, 6\)"):
        env.step(np.zeros((1, 6)))
    with pytest.raises(ValueError, match=r"action: expected a float64 array of shape \(6,\), got dtype complex128"):
        env.step(np.zeros(6, dtype=complex))
    with pytest.raises(TypeError, match="action"):
        env.step(None)
    nan = np.zeros(6)
    nan[2] = np.nan
    with pytest.raises(mjarm.Error, match=r"action\[2\]"):
        env.step(nan)
    # int and float32 arrays and lists are converted, a strided slice copied (never misread)
    strided = np.zeros(12)
    strided[::2] = 0.01
    a = env.step(strided[::2])
    b = reach(time_limit=0.04)
    b.reset(0)
    assert b.step([0.01] * 6).values.tobytes() == a.values.tobytes()
    assert env.step(np.zeros(6, dtype=np.float32)).last()
    with pytest.raises(mjarm.Error, match="after the last step"):
        env.step(np.zeros(6))  # after LAST without reset
    with pytest.raises(mjarm.Error, match="reahc"):
        mjarm.Environment("reahc")
    with pytest.raises(mjarm.Error, match="object_pose"):
        reach(observations=["joint_positions", "object_pose"])
    with pytest.raises(mjarm.Error, match="no_such"):
        reach(observations=["no_such"])
    with pytest.raises(mjarm.Error, match="unknown option 'time_limt'"):
        reach(time_limt=1.0)
    with pytest.raises(mjarm.Error, match="whole multiple"):
        reach(control_period=0.015)
    with pytest.raises(mjarm.Error, match="seed"):
        env.reset(-1)
    with pytest.raises(mjarm.Error, match="seed"):
        env.reset(2**64)
    with pytest.raises(mjarm.Error, match="seed"):
        env.reset(1.5)
    assert env.reset(np.int64(3)).values.tobytes() == env.reset(3).values.tobytes()
    with pytest.raises(mjarm.Error, match="action space"):
        reach(action_space="joint_torks")


def test_options_and_action_spaces():
    options = mjarm.EnvironmentOptions()
    options.action_space = "joint_torques"
    options.observations = ["joint_positions", "sensor:arm/ft_force"]
    env = mjarm.Environment("reach", options, time_limit=0.1)
    assert env.options.action_space == mjarm.ActionSpace.joint_torques
    assert env.options.time_limit == 0.1 and options.time_limit == 10.0  # overrides copy
    assert env.action_spec().shape == (7,) and list(env.observation_spec()) == options.observations
    assert env.physics_steps_per_step == 10


def test_task_options_by_name():
    names = [p["name"] for p in mjarm.env_task_parameters("reach")]
    assert "success-distance" in names and "target-center" in names
    # within 0.9 m of any target: the reach succeeds on its first step
    env = mjarm.Environment("reach", task_options={"success-distance": 0.9}, time_limit=0.2)
    env.reset(1)
    assert env.step(np.zeros(6)).last()
    with pytest.raises(mjarm.Error, match="unknown parameter 'sucess-distance'"):
        mjarm.Environment("reach", task_options={"sucess-distance": 0.9})


# --- the vectorized environment ---------------------------------------------------------------

def rollout(threads, steps=30):
    vec = mjarm.VectorEnvironment("reach", 4, threads, time_limit=0.2, seed=9)
    rng = np.random.default_rng(3)
    spec = vec.action_spec()
    out = [vec.reset()]
    for _ in range(steps):
        out.append(vec.step(rng.uniform(spec.minimum, spec.maximum, size=(4, 6))))
    return out


def test_vector_batches_and_autoreset():
    batches = rollout(2)
    first = batches[0]
    assert np.all(first.step_type == int(mjarm.StepType.FIRST)) and np.all(np.isnan(first.reward))
    for b in batches:
        assert b.values.shape == (4, 27) and b.values.flags.c_contiguous and b.values.dtype == np.float64
        assert b.reward.shape == (4,) and b.discount.shape == (4,) and b.step_type.shape == (4,)
        for name, spec in mjarm.Environment("reach").observation_spec().items():
            assert b.observation[name].shape == (4,) + spec.shape
            assert b.observation[name].flags.c_contiguous
    # 10 steps an episode: LAST at step 10 (truncated, discount 1), FIRST at 11, as in C++
    assert np.all(batches[10].last()) and np.all(batches[10].discount == 1.0)
    assert np.all(batches[10].end == int(mjarm.EpisodeEnd.truncated))
    assert np.all(batches[11].first()) and np.all(np.isnan(batches[11].reward))
    assert np.all(batches[12].mid())
    # copies: a batch kept is not changed by the later steps, and shares nothing with them
    assert not np.shares_memory(batches[5].values, batches[6].values)
    assert not np.array_equal(batches[5].values, batches[6].values)
    # the same arrays bit for bit on one thread
    one = rollout(1)
    gc.collect()  # the environments of both rollouts are gone: the batches still read (ASan)
    for a, b in zip(batches, one):
        assert a.values.tobytes() == b.values.tobytes()
        assert a.reward.tobytes() == b.reward.tobytes()


def test_vector_bad_input():
    vec = mjarm.VectorEnvironment("reach", 3, 1, time_limit=0.1)
    with pytest.raises(mjarm.Error, match="reset"):
        vec.step(np.zeros((3, 6)))
    vec.reset()
    with pytest.raises(ValueError, match=r"actions: expected shape \(3, 6\), got \(6,\)"):
        vec.step(np.zeros(6))
    with pytest.raises(ValueError, match=r"actions: expected shape \(3, 6\), got \(2, 6\)"):
        vec.step(np.zeros((2, 6)))
    bad = np.zeros((3, 6))
    bad[1, 4] = np.inf
    with pytest.raises(mjarm.Error, match="1"):
        vec.step(bad)
    with pytest.raises(mjarm.Error):
        mjarm.VectorEnvironment("reach", 0, 1)
    # a transposed (non-contiguous) array is read by its shape, never by its memory order
    actions = np.arange(18, dtype=float).reshape(6, 3).T * 1e-3  # (3, 6), Fortran order
    a = vec.step(actions)
    b = mjarm.VectorEnvironment("reach", 3, 1, time_limit=0.1)
    b.reset()
    assert b.step(np.ascontiguousarray(actions)).values.tobytes() == a.values.tobytes()


def test_one_environment_from_two_threads_is_refused():
    """Both threads step until one is refused (the other stepping at that moment); with the GIL
    released in a step that comes as soon as the OS runs both at once, however fast or busy the
    machine — a count of steps only caps a failing run (no refusal at all)."""
    env = reach(time_limit=100.0)
    env.reset(0)
    errors, done = [], threading.Event()

    def worker():
        try:
            for _ in range(20000):
                if errors:
                    break
                try:
                    env.step(np.zeros(6))
                except mjarm.Error as e:
                    errors.append(str(e))
        finally:
            done.set()

    t = threading.Thread(target=worker)
    t.start()
    while not done.is_set() and not errors:
        try:
            env.step(np.zeros(6))
        except mjarm.Error as e:
            errors.append(str(e))
    t.join()
    assert errors and "another thread" in errors[0]


def test_gil_released_while_a_batch_steps():
    """The main thread's Python code runs while another thread is inside VectorEnvironment.step
    (with the GIL held it could not run at all). Needs no free core: the OS time-slices."""
    vec = mjarm.VectorEnvironment("reach", 32, 1, time_limit=100.0)
    vec.reset()
    actions = np.zeros((32, 6))
    ran, steps = runs_beside(lambda: [vec.step(actions) for _ in range(10)], most=200)
    assert ran and len(steps) == 10 and len(steps[-1].reward) == 32


def test_the_gil_check_tells_a_call_that_keeps_it():
    """runs_beside (conftest.py) can fail: pure Python keeps the GIL (every call of the cap, the
    other thread never runs); a call that sleeps releases it."""
    ran, total = runs_beside(lambda: sum(range(100000)), most=5)
    assert not ran and total == 4999950000
    ran, _ = runs_beside(lambda: time.sleep(0.001))
    assert ran


# --- the Gymnasium-style adapter -------------------------------------------------------------

def test_gym_reset_step_conventions():
    from gymnasium.spaces import Box, Dict
    from mjarm.gym import GymEnv

    env = GymEnv("reach", time_limit=0.1)
    assert isinstance(env.action_space, Box) and isinstance(env.observation_space, Dict)
    # the spec's order, not gymnasium's default sorting by name
    assert list(env.observation_space.keys()) == list(env.env.observation_spec())
    obs, info = env.reset(seed=5)
    assert isinstance(obs, dict) and isinstance(info, dict) and env.observation_space.contains(obs)
    assert info["episode_seed"] == 5
    native = mjarm.Environment("reach", time_limit=0.1).reset(5)
    assert all(np.array_equal(obs[k], native.observation[k]) for k in obs)
    env.action_space.seed(1)
    a = env.action_space.sample()
    env.action_space.seed(1)
    assert np.array_equal(a, env.action_space.sample()) and env.action_space.contains(a)
    assert a.dtype == np.float64 and a.shape == (6,)
    assert not env.action_space.contains(np.full(6, 1.0)) and not env.action_space.contains(np.zeros(5))
    results = [env.step(env.action_space.sample()) for _ in range(5)]
    for obs, reward, terminated, truncated, info in results:
        assert isinstance(reward, float) and isinstance(terminated, bool) and isinstance(truncated, bool)
    assert [r[3] for r in results] == [False] * 4 + [True]  # the time limit: truncated
    assert not any(r[2] for r in results)
    assert results[-1][4]["discount"] == 1.0 and results[-1][4]["end"] == mjarm.EpisodeEnd.truncated
    with pytest.raises(mjarm.Error):
        env.step(np.zeros(6))  # after the end without reset
    assert env.render() is None
    env.close()
    # termination: discount 0 -> terminated, not truncated
    env = GymEnv("reach", time_limit=3.0)
    obs, _ = env.reset(seed=7)
    terminated = truncated = False
    while not (terminated or truncated):
        action = np.zeros(6)
        action[:3] = 0.3 * obs["target_offset"]
        obs, reward, terminated, truncated, info = env.step(action)
    assert terminated and not truncated and info["discount"] == 0.0
    with pytest.raises(ValueError, match=r"action: expected shape \(6,\)"):
        env.reset()
        env.step(np.zeros(4))


def test_gym_seeding_and_flattened_observations():
    from gymnasium.spaces import Box
    from mjarm.gym import GymEnv

    a, b = GymEnv("reach", flatten=True), GymEnv("reach", flatten=True)
    assert isinstance(a.observation_space, Box) and a.observation_space.shape == (27,)
    oa, _ = a.reset(seed=3)
    ob, _ = b.reset(seed=3)
    assert oa.shape == (27,) and np.array_equal(oa, ob)
    # reset() after reset(seed) continues a sequence seeded by that seed
    oa, ia = a.reset()
    ob, ib = b.reset()
    assert np.array_equal(oa, ob) and ia["episode_seed"] == ib["episode_seed"] != 3
    assert a.observation_space.dtype == np.float64 and a.action_space.dtype == np.float64
    with pytest.raises(ValueError):
        a.reset(options={"x": 1})


def test_gym_vector_adapter():
    from mjarm.gym import GymVectorEnv

    env = GymVectorEnv("reach", 3, threads=2, time_limit=0.06)  # 3 steps an episode
    assert env.action_space.shape == (3, 6) and env.single_action_space.shape == (6,)
    obs, infos = env.reset(seed=4)
    assert obs["joint_positions"].shape == (3, 7) and np.all(infos["first"])
    env.action_space.seed(0)
    flags = []
    for _ in range(4):
        obs, rewards, terminations, truncations, infos = env.step(env.action_space.sample())
        assert rewards.shape == (3,) and terminations.dtype == bool
        flags.append((truncations.copy(), infos["first"].copy(), rewards.copy()))
    assert np.all(flags[2][0])  # the third step reached the time limit: truncated
    # next-step autoreset: the following step resets, reward 0, no flags
    assert np.all(flags[3][1]) and np.all(flags[3][2] == 0.0) and not np.any(flags[3][0])
    again = GymVectorEnv("reach", 3, threads=1, time_limit=0.06)
    o2, _ = again.reset(seed=4)
    assert np.array_equal(o2["ee_pose"], env.reset(seed=4)[0]["ee_pose"])


def test_closed_environments_stay_closed():
    """issue 29: close() then reset() worked as if the environment had never been closed."""
    from mjarm.dm_env import DmEnv
    from mjarm.gym import GymEnv, GymVectorEnv

    for task in mjarm.env_task_names():
        env = mjarm.Environment(task)
        env.reset(1)
        env.close()
        env.close()
        assert env.closed
        with pytest.raises(mjarm.Error, match=f"environment '{task}': reset\\(\\) after close\\(\\)"):
            env.reset(1)
        with pytest.raises(mjarm.Error, match="step\\(\\) after close\\(\\)"):
            env.step(np.zeros(env.action_spec().shape))
    with mjarm.Environment("reach") as env:
        env.reset()
    with pytest.raises(mjarm.Error, match="after close"):
        env.reset()

    batch = mjarm.VectorEnvironment("reach", 2)
    batch.reset()
    batch.close()
    assert batch.closed
    with pytest.raises(mjarm.Error, match="vector environment 'reach': reset\\(\\) after close"):
        batch.reset()
    with pytest.raises(mjarm.Error, match="step\\(\\) after close"):
        batch.step(np.zeros((2,) + batch.action_spec().shape))

    dm = DmEnv("reach")
    dm.reset()
    dm.close()
    with pytest.raises(mjarm.Error, match="after close"):
        dm.reset()
    gym = GymEnv("reach")
    gym.reset(seed=1)
    gym.close()
    with pytest.raises(mjarm.Error, match="after close"):
        gym.reset(seed=2)
    vector = GymVectorEnv("reach", 2)
    vector.reset(seed=1)
    vector.close()
    for seed in (None, 3):  # a seed rebuilt the batch: it must not reopen it
        with pytest.raises(mjarm.Error, match="after close"):
            vector.reset(seed=seed)
