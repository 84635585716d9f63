"""Gymnasium adapters of mjarm's environments (needs the gymnasium package, pinned in
python/requirements.txt): ``GymEnv`` is a ``gymnasium.Env``, ``GymVectorEnv`` a
``gymnasium.vector.VectorEnv``, with Gymnasium 1.x's conventions:

- ``GymEnv.reset(*, seed=None, options=None) -> (obs, info)``;
- ``GymEnv.step(action) -> (obs, reward, terminated, truncated, info)``: ``terminated`` when the
  episode ended with discount 0 (the task ended it, or the physics diverged), ``truncated`` when
  it ended with discount 1 (the time limit: the state is not terminal);
- ``action_space`` is a float64 ``gymnasium.spaces.Box``; ``observation_space`` a
  ``gymnasium.spaces.Dict`` of float64 boxes in the environment's spec order (or one Box with
  ``flatten=True``);
- ``close()``; ``render()`` returns None (``render_mode`` is None: use ``mjarm.OffscreenRenderer``).

Observations are a dict name -> float64 array by default (the environment's arrays, in its
spec order), or with ``flatten=True`` one float64 vector (the arrays back to back in that order,
as gymnasium's FlattenObservation would give), the observation space then one Box.
Either way the arrays are the time step's own copies: keeping them across steps is safe.

``GymVectorEnv`` is the vectorized form: batch arrays with row i for environment i and
gymnasium's "next step" autoreset, which is mjarm's: the step after a row's episode ended resets
that row (its action is ignored) and returns its first observation with reward 0 and
terminated = truncated = False.
"""
import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from . import _mjarm

__all__ = ["GymEnv", "GymVectorEnv"]


def _box(spec):
    shape = tuple(spec.shape)
    return spaces.Box(np.broadcast_to(spec.minimum, shape), np.broadcast_to(spec.maximum, shape),
                      shape, np.float64)


def _observation_space(specs, flatten):
    if flatten:
        low = np.concatenate([s.minimum.ravel() for s in specs.values()])
        high = np.concatenate([s.maximum.ravel() for s in specs.values()])
        return spaces.Box(low, high, low.shape, np.float64)
    # a sequence of pairs keeps the spec order (a plain dict would be sorted by name)
    return spaces.Dict([(name, _box(s)) for name, s in specs.items()])


class GymEnv(gymnasium.Env):
    """A ``gymnasium.Env`` on :class:`mjarm.Environment`.

    ``GymEnv(task, flatten=False, options=None, **overrides)`` takes the arguments of
    ``mjarm.Environment`` (or ``env=`` an existing one). Seeding: ``reset(seed=s)`` starts the
    episode of seed ``s`` (the same as ``Environment.reset(s)``) and reseeds ``np_random``, the
    sequence the following ``reset()`` calls draw their episode seeds from; a ``reset()`` before
    any seed uses the environment's own sequence (``EnvironmentOptions.seed``). ``info`` holds
    ``discount``, ``end`` (an EpisodeEnd), ``episode_seed``, ``step`` and ``clipped_values`` (of
    this episode)."""

    metadata = {"render_modes": []}

    def __init__(self, task=None, flatten=False, options=None, env=None, **overrides):
        if env is None:
            if task is None:
                raise TypeError("GymEnv: give a task name or env=")
            env = _mjarm.Environment(task, options, **overrides)
        elif task is not None or options is not None or overrides:
            raise TypeError("GymEnv: give either env= or a task with options, not both")
        self.env = env
        self.flatten = flatten
        self.action_space = _box(env.action_spec())
        self.observation_space = _observation_space(env.observation_spec(), flatten)

    def _obs(self, ts):
        return ts.values if self.flatten else ts.observation

    def _info(self, ts):
        return {"discount": ts.discount, "end": ts.end, "episode_seed": self.env.episode_seed,
                "step": self.env.steps, "clipped_values": self.env.episode_clips.values}

    def reset(self, *, seed=None, options=None):
        """Starts an episode: ``(observation, info)``. ``options`` is accepted and must be None
        or empty (the environment has no per-episode options)."""
        if options:
            raise ValueError(f"GymEnv.reset: no reset options are supported, got {options!r}")
        seeded = self._np_random is not None
        super().reset(seed=seed)  # reseeds np_random when a seed is given
        if seed is not None:
            ts = self.env.reset(seed)
        elif seeded:
            ts = self.env.reset(int(self.np_random.integers(0, 2**63)))
        else:
            ts = self.env.reset()
        return self._obs(ts), self._info(ts)

    def step(self, action):
        """One step: ``(observation, reward, terminated, truncated, info)``."""
        ts = self.env.step(action)
        terminated = ts.last() and ts.discount == 0.0
        truncated = ts.last() and not terminated
        return self._obs(ts), ts.reward, terminated, truncated, self._info(ts)

    def render(self):
        """None: no render mode (render frames with mjarm.OffscreenRenderer)."""
        return None

    def close(self):
        """Closes the environment: reset() and step() then raise mjarm.Error."""
        self.env.close()

    def __repr__(self):
        return f"GymEnv({self.env.task!r}, flatten={self.flatten})"


class GymVectorEnv(VectorEnv):
    """A ``gymnasium.vector.VectorEnv`` on :class:`mjarm.VectorEnvironment`:
    ``GymVectorEnv(task, num_envs, threads=1, flatten=False, options=None, **overrides)``.

    ``reset(seed=s)`` rebuilds the batch with ``EnvironmentOptions.seed = s`` (environment i
    then draws its episode seeds from splitmix64(s + i)); ``reset()`` resets every row with the
    next seed of its sequence. ``step(actions)`` with actions (num_envs, action size) returns
    ``(obs, rewards, terminations, truncations, infos)``: obs a dict of (num_envs, *shape) arrays
    (or (num_envs, size) flattened), the others (num_envs,) arrays, and the "next step"
    autoreset (a row reset by this step has reward 0 and neither flag set; ``infos['first']``
    marks those rows)."""

    metadata = {"render_modes": [], "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, task, num_envs, threads=1, flatten=False, options=None, **overrides):
        self._args = (task, num_envs, threads, options, overrides)
        self.env = _mjarm.VectorEnvironment(task, num_envs, threads, options, **overrides)
        self.num_envs = num_envs
        self.flatten = flatten
        self.single_action_space = _box(self.env.action_spec())
        self.action_space = batch_space(self.single_action_space, num_envs)
        self.single_observation_space = _observation_space(self.env.observation_spec(), flatten)
        self.observation_space = batch_space(self.single_observation_space, num_envs)

    def _obs(self, batch):
        return batch.values if self.flatten else batch.observation

    @staticmethod
    def _infos(batch):
        return {"discount": batch.discount, "end": batch.end, "first": batch.first()}

    def reset(self, *, seed=None, options=None):
        """Resets every row: ``(obs, infos)``."""
        if options:
            raise ValueError(f"GymVectorEnv.reset: no reset options are supported, got {options!r}")
        if seed is not None and not self.env.closed:  # a closed batch stays closed
            task, n, threads, opts, overrides = self._args
            overrides = dict(overrides, seed=seed)
            self.env = _mjarm.VectorEnvironment(task, n, threads, opts, **overrides)
        batch = self.env.reset()
        return self._obs(batch), self._infos(batch)

    def step(self, actions):
        """One step of every row: ``(obs, rewards, terminations, truncations, infos)``."""
        batch = self.env.step(actions)
        last = batch.last()
        terminations = last & (batch.discount == 0.0)
        truncations = last & ~terminations
        rewards = np.nan_to_num(batch.reward, nan=0.0)
        return self._obs(batch), rewards, terminations, truncations, self._infos(batch)

    def render(self):
        """None: no render mode."""
        return None

    def close_extras(self, **kwargs):
        """Closes the batch: reset() and step() then raise mjarm.Error."""
        self.env.close()

    def __repr__(self):
        return f"GymVectorEnv({self.env.task!r}, num_envs={self.num_envs})"
