"""Tasks written in Python (mjarm.EnvTask subclasses) run by the C++ environment: their own
action mapped onto an action space, observations, reward, termination and randomization, in an
Environment and a VectorEnvironment; a hook that raises; bad tasks."""
import numpy as np
import pytest

import mjarm

PI = np.pi
ROWS = [dict(d=0.1625, alpha=PI / 2), dict(a=-0.425), dict(a=-0.3922),
        dict(d=0.1333, alpha=PI / 2), dict(d=0.0997, alpha=-PI / 2), dict(d=0.0996)]
HOME = np.array([0.0, -1.2, 1.4, -1.8, -1.57, 0.0])


def ur5e():
    arm = mjarm.DhArm(name="ur5e_dh", links=[mjarm.DhLink(**row) for row in ROWS],
                      actuators=mjarm.DhActuators.motor, effort=150.0, damping=0.5)
    return mjarm.dh_robot(arm)


ROBOT = ur5e()


class Reach(mjarm.EnvTask):
    """Bring the tool to a random point with a 3-D velocity command."""
    name = "py_reach"
    description = "tool to a random point, by velocity"

    def __init__(self, fail_at=None):
        super().__init__(ROBOT, "end")
        self.fail_at = fail_at
        self.target = np.zeros(3)

    def action_spec(self):
        return mjarm.ArraySpec("velocity", [3], [-0.25] * 3, [0.25] * 3)

    def map_action(self, context, action):
        return np.concatenate([action, np.zeros(3)])  # ee_velocities: [v; w]

    def initialize_episode(self, sim, rng):
        sim.reset()
        sim.set_state(HOME, np.zeros(6))
        start = mjarm.forward_kinematics(self.chain_object(), HOME).p
        self.target = start + rng.uniform([-0.1, -0.1, -0.1], [0.1, 0.1, 0.1])

    def chain_object(self):
        return mjarm.Chain(ROBOT, "end")

    def observation_specs(self):
        return [mjarm.ArraySpec("target", [3]), mjarm.ArraySpec("error", [3])]

    def default_observations(self):
        return ["target", "error", "joint_positions"]

    def observe(self, name, context):
        return self.target if name == "target" else self.target - context.X_WE.p

    def reward(self, context):
        if self.fail_at is not None and context.step == self.fail_at:
            raise ZeroDivisionError("the task's reward failed on purpose")
        return -float(np.linalg.norm(context.X_WE.p - self.target))

    def terminated(self, context):
        return np.linalg.norm(context.X_WE.p - self.target) < 0.01


def proportional(ts, gain=2.0):
    return np.clip(gain * ts.observation["error"], -0.25, 0.25)


def test_a_python_task_defines_the_action_observations_reward_and_termination():
    env = mjarm.Environment(Reach(), action_space="ee_velocities", time_limit=4.0)
    assert env.task == "py_reach"
    spec = env.action_spec()
    assert spec.name == "velocity" and tuple(spec.shape) == (3,)
    assert list(env.observation_spec()) == ["target", "error", "joint_positions"]
    ts = env.reset(seed=3)
    first_error = np.linalg.norm(ts.observation["error"])
    steps = 0
    while not ts.last():
        ts = env.step(proportional(ts))
        steps += 1
    assert env.end == mjarm.EpisodeEnd.terminated, "the proportional policy reaches the target"
    assert ts.discount == 0.0
    assert np.linalg.norm(ts.observation["error"]) < 0.01 < first_error
    assert ts.reward == pytest.approx(-np.linalg.norm(ts.observation["error"]), abs=1e-9)
    # the same seed and actions give the same episode, bit for bit
    again = env.reset(seed=3)
    np.testing.assert_array_equal(again.observation["target"],
                                  env.reset(seed=3).observation["target"])
    other = env.reset(seed=4)
    assert not np.array_equal(other.observation["target"], again.observation["target"])


def test_a_random_policy_runs_a_few_hundred_steps_with_clipping_counted():
    env = mjarm.Environment(Reach(), action_space="ee_velocities", time_limit=1.0)
    rng = np.random.default_rng(0)
    episodes, steps = 0, 0
    ts = env.reset(seed=0)
    while steps < 300:
        ts = env.step(rng.uniform(-0.4, 0.4, 3))  # some values past the bounds
        steps += 1
        assert np.isfinite(ts.reward)
        if ts.last():
            episodes += 1
            ts = env.reset()
    assert episodes >= 5
    assert env.total_clips.values > 0


def test_a_hook_that_raises_ends_the_episode_and_reaches_the_caller():
    env = mjarm.Environment(Reach(fail_at=2), action_space="ee_velocities")
    env.reset(seed=1)
    env.step(np.zeros(3))
    with pytest.raises(ZeroDivisionError, match="on purpose") as raised:
        env.step(np.zeros(3))
    assert "reward" in "".join(str(f.name) for f in raised.traceback)
    with pytest.raises(mjarm.Error, match="after the last step"):
        env.step(np.zeros(3))
    env.reset(seed=1)  # usable again
    assert env.step(np.zeros(3)).mid()


def test_a_vector_environment_runs_a_clone_per_environment():
    with mjarm.VectorEnvironment(Reach(), 4, threads=2, action_space="ee_velocities",
                                 time_limit=0.5) as v:
        ts = v.reset()
        targets = ts.observation["target"]
        assert targets.shape == (4, 3)
        assert len({tuple(row) for row in targets}) == 4, "each environment its own target"
        for _ in range(30):
            ts = v.step(np.clip(2.0 * ts.observation["error"], -0.25, 0.25))
        assert np.all(np.isfinite(ts.reward))


def test_bad_tasks_are_refused():
    with pytest.raises(TypeError, match="subclass of mjarm.EnvTask"):
        mjarm.Environment(object())

    class Unbounded(Reach):
        def action_spec(self):
            return mjarm.ArraySpec("velocity", [3])

    with pytest.raises(mjarm.Error, match="needs finite bounds"):
        mjarm.Environment(Unbounded(), action_space="ee_velocities")

    class WrongSize(Reach):
        def map_action(self, context, action):
            return action  # 3 values for a 6-value space

    env = mjarm.Environment(WrongSize(), action_space="ee_velocities")
    env.reset(seed=0)
    with pytest.raises(ValueError, match="map_action"):
        env.step(np.zeros(3))
    with pytest.raises(mjarm.Error, match="task_options"):
        mjarm.Environment(Reach(), task_options={"x": 1})


def test_noise_and_latency_on_any_task_show_in_the_gymnasium_spaces():
    import mjarm.gym

    env = mjarm.gym.GymEnv("reach", observation_noise=0.05, action_latency=1)
    clean = mjarm.gym.GymEnv("reach")
    # some observation of the task is bounded (the pose's quaternion); with noise none is
    assert any(np.isfinite(box.low).any() for box in clean.observation_space.values())
    assert all(np.isinf(box.low).all() and np.isinf(box.high).all()
               for box in env.observation_space.values())
    a, _ = env.reset(seed=4)
    b, _ = mjarm.gym.GymEnv("reach", observation_noise=0.05, action_latency=1).reset(seed=4)
    np.testing.assert_array_equal(a["joint_positions"], b["joint_positions"])
    c, _ = clean.reset(seed=4)
    assert not np.array_equal(a["joint_positions"], c["joint_positions"])
    # a Python task takes them too
    task_env = mjarm.Environment(Reach(), action_space="ee_velocities", observation_noise=0.01,
                                 action_latency=3)
    assert task_env.options.action_latency == 3
    task_env.reset(seed=0)
    task_env.step(np.zeros(3))
    with pytest.raises(mjarm.Error, match="action_latency"):
        mjarm.Environment("reach", action_latency=-1)


def test_the_overhead_benchmark_runs_a_small_count():
    import json
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-m", "mjarm.bench_task", "--steps", "20", "--rounds",
                          "1", "--json"], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    figures = json.loads(out.stdout)
    assert figures["cpp_us_per_step"] > 0 and figures["python_us_per_step"] > 0
    assert figures["ratio"] == pytest.approx(figures["python_us_per_step"] /
                                             figures["cpp_us_per_step"])


def test_the_overhead_benchmark_refuses_a_bad_count(capsys):
    import mjarm.bench_task

    with pytest.raises(SystemExit) as bad:  # its main, in this process: no interpreter to start
        mjarm.bench_task.main(["--steps", "1"])
    assert bad.value.code == 2 and "--steps" in capsys.readouterr().err


def test_pictures_are_observations_and_show_in_the_gymnasium_spaces():
    import mjarm.gym

    env = mjarm.Environment("reach", observations=["pixels:free", "depth:free",
                                                   "joint_positions"],
                            pixels_width=40, pixels_height=30)
    ts = env.reset(seed=0)
    rgb, depth = ts.observation["pixels:free"], ts.observation["depth:free"]
    assert rgb.shape == (30, 40, 3) and depth.shape == (30, 40)
    assert 0.0 <= rgb.min() and rgb.max() <= 255.0 and rgb.max() - rgb.min() > 50
    assert np.all(np.isfinite(depth)) and depth.min() > 0.0
    gym = mjarm.gym.GymEnv("reach", observations=["pixels:free"], pixels_width=40,
                           pixels_height=30)
    assert gym.observation_space["pixels:free"].shape == (30, 40, 3)
    assert "pixels:free" in mjarm.env_observations("reach")
    with pytest.raises(mjarm.Error, match="no such camera"):
        mjarm.Environment("reach", observations=["pixels:nowhere"])
