"""Gymnasium-style adapters of mjarm's environments, written here without the gymnasium package
(Debian 12 does not have it), following its conventions (Gymnasium 1.x):

- ``GymEnv.reset(*, seed=None, options=None) -> (obs, info)``;
- ``GymEnv.step(action) -> (obs, reward, terminated, truncated, info)``: ``terminated`` when the
  episode ended with discount 0 (the task ended it, or the physics diverged), ``truncated`` when
  it ended with discount 1 (the time limit: the state is not terminal);
- ``action_space`` and ``observation_space`` are :class:`Box` (low, high, shape, dtype,
  ``sample()`` from a seeded ``np.random.Generator``, ``contains()``, ``seed()``) or, for
  observations by default, a :class:`Dict` of boxes;
- ``close()``; ``render()`` returns None (``render_mode`` is None: use ``mjarm.OffscreenRenderer``).

Observations are a dict name -> float64 array by default (the environment's arrays, in its
spec order), or with ``flatten=True`` one float64 vector (the arrays back to back in that order,
as gymnasium's FlattenObservation would give), the observation space then one Box.
Either way the arrays are the time step's own copies: keeping them across steps is safe.

``GymVectorEnv`` is the vectorized form (gymnasium's VectorEnv): batch arrays with row i for
environment i and gymnasium's "next step" autoreset, which is mjarm's: the step after a row's
episode ended resets that row (its action is ignored) and returns its first observation with
reward 0 and terminated = truncated = False.
"""
import numpy as np

from . import _mjarm

__all__ = ["Box", "Dict", "GymEnv", "GymVectorEnv"]


class Box:
    """A box in R^n (gymnasium.spaces.Box): ``low`` and ``high`` arrays of ``shape``, ``dtype``
    float64. ``sample()`` draws from ``np_random`` (seed it with ``seed()``): uniform where both
    bounds are finite, normal where neither is, shifted exponential where one is."""

    def __init__(self, low, high, shape=None, dtype=np.float64, seed=None):
        self.dtype = np.dtype(dtype)
        if shape is None:
            shape = np.shape(low) if np.ndim(low) else np.shape(high)
        self.shape = tuple(int(d) for d in shape)
        self.low = np.broadcast_to(np.asarray(low, dtype=self.dtype), self.shape).copy()
        self.high = np.broadcast_to(np.asarray(high, dtype=self.dtype), self.shape).copy()
        if np.any(self.low > self.high):
            raise ValueError("Box: low must not exceed high")
        self._np_random = None
        if seed is not None:
            self.seed(seed)

    @property
    def np_random(self):
        """The generator of ``sample()`` (seeded from the OS on first use unless ``seed()`` was
        called)."""
        if self._np_random is None:
            self.seed()
        return self._np_random

    def seed(self, seed=None):
        """Seeds ``np_random`` with ``np.random.default_rng(seed)``; returns ``[seed]``."""
        self._np_random = np.random.default_rng(seed)
        return [seed]

    def is_bounded(self, manner="both"):
        """True when every element is bounded: ``manner`` 'both', 'below' or 'above'."""
        below = bool(np.all(np.isfinite(self.low)))
        above = bool(np.all(np.isfinite(self.high)))
        if manner == "both":
            return below and above
        if manner == "below":
            return below
        if manner == "above":
            return above
        raise ValueError("manner must be 'both', 'below' or 'above'")

    def sample(self):
        """A random element (gymnasium's rules: uniform on bounded elements, normal on unbounded
        ones, exponential on half-bounded ones)."""
        rng = self.np_random
        below, above = np.isfinite(self.low), np.isfinite(self.high)
        out = np.empty(self.shape, dtype=self.dtype)
        both = below & above
        none = ~below & ~above
        low_only = below & ~above
        high_only = ~below & above
        out[none] = rng.normal(size=none[none].shape)
        out[low_only] = rng.exponential(size=low_only[low_only].shape) + self.low[low_only]
        out[high_only] = -rng.exponential(size=high_only[high_only].shape) + self.high[high_only]
        out[both] = rng.uniform(low=self.low[both], high=self.high[both], size=both[both].shape)
        return out.astype(self.dtype)

    def contains(self, x):
        """True when ``x`` has this shape, a dtype castable to float64 and lies within the
        bounds."""
        if not isinstance(x, np.ndarray):
            try:
                x = np.asarray(x, dtype=self.dtype)
            except (ValueError, TypeError):
                return False
        return bool(np.can_cast(x.dtype, self.dtype) and x.shape == self.shape
                    and np.all(x >= self.low) and np.all(x <= self.high))

    def __contains__(self, x):
        return self.contains(x)

    def __eq__(self, other):
        return (isinstance(other, Box) and self.shape == other.shape and self.dtype == other.dtype
                and np.array_equal(self.low, other.low) and np.array_equal(self.high, other.high))

    def __repr__(self):
        low = self.low.min() if self.low.size else 0.0
        high = self.high.max() if self.high.size else 0.0
        return f"Box({low}, {high}, {self.shape}, {self.dtype})"


class Dict:
    """A dict of spaces (gymnasium.spaces.Dict), kept in the given order (the environment's
    spec order)."""

    def __init__(self, spaces, seed=None):
        self.spaces = dict(spaces)
        if seed is not None:
            self.seed(seed)

    def seed(self, seed=None):
        """Seeds every subspace from one generator seeded with ``seed``; returns their seeds."""
        rng = np.random.default_rng(seed)
        seeds = [int(s) for s in rng.integers(0, 2**63 - 1, size=len(self.spaces))]
        for space, s in zip(self.spaces.values(), seeds):
            space.seed(s)
        return seeds

    def sample(self):
        """A dict of one sample per subspace."""
        return {name: space.sample() for name, space in self.spaces.items()}

    def contains(self, x):
        """True when ``x`` is a dict with exactly these keys, each value in its space."""
        return (isinstance(x, dict) and x.keys() == self.spaces.keys()
                and all(self.spaces[k].contains(v) for k, v in x.items()))

    def __contains__(self, x):
        return self.contains(x)

    def __getitem__(self, key):
        return self.spaces[key]

    def keys(self):
        return self.spaces.keys()

    def __len__(self):
        return len(self.spaces)

    def __repr__(self):
        return "Dict(" + ", ".join(f"{k!r}: {v}" for k, v in self.spaces.items()) + ")"


def _box(spec, batch=None):
    shape = tuple(spec.shape) if batch is None else (batch,) + tuple(spec.shape)
    return Box(np.broadcast_to(spec.minimum, shape), np.broadcast_to(spec.maximum, shape), shape)


def _flat_box(specs, batch=None):
    low = np.concatenate([s.minimum.ravel() for s in specs.values()])
    high = np.concatenate([s.maximum.ravel() for s in specs.values()])
    if batch is not None:
        low, high = np.tile(low, (batch, 1)), np.tile(high, (batch, 1))
    return Box(low, high, low.shape)


class GymEnv:
    """A Gymnasium-style environment on :class:`mjarm.Environment`.

    ``GymEnv(task, flatten=False, options=None, **overrides)`` takes the arguments of
    ``mjarm.Environment`` (or ``env=`` an existing one). Seeding: ``reset(seed=s)`` starts the
    episode of seed ``s`` (the same as ``Environment.reset(s)``) and reseeds the sequence the
    following ``reset()`` calls draw their episode seeds from; a ``reset()`` before any seed
    uses the environment's own sequence (``EnvironmentOptions.seed``). ``info`` holds
    ``discount``, ``end`` (an EpisodeEnd), ``episode_seed``, ``step`` and ``clipped_values`` (of
    this episode)."""

    metadata = {"render_modes": []}
    render_mode = None
    spec = None
    reward_range = (-float("inf"), float("inf"))

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
        specs = env.observation_spec()
        self.observation_space = (_flat_box(specs) if flatten
                                  else Dict({name: _box(s) for name, s in specs.items()}))
        self._seeds = None
        self._np_random = None

    @property
    def unwrapped(self):
        return self

    @property
    def np_random(self):
        """The generator of the episode seeds (seeded by ``reset(seed=...)``)."""
        if self._np_random is None:
            self._np_random = np.random.default_rng()
        return self._np_random

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
        if seed is not None:
            self._np_random = np.random.default_rng(seed)
            ts = self.env.reset(seed)
        elif self._np_random is not None:
            ts = self.env.reset(int(self._np_random.integers(0, 2**63)))
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
        """Closes the environment (nothing to release)."""
        self.env.close()

    def __enter__(self):
        return self

    def __exit__(self, *args):
        self.close()
        return False

    def __repr__(self):
        return f"GymEnv({self.env.task!r}, flatten={self.flatten})"


class GymVectorEnv:
    """A Gymnasium-style vectorized environment (gymnasium's VectorEnv) on
    :class:`mjarm.VectorEnvironment`: ``GymVectorEnv(task, num_envs, threads=1, flatten=False,
    options=None, **overrides)``.

    ``reset(seed=s)`` rebuilds the batch with ``EnvironmentOptions.seed = s`` (environment i
    then draws its episode seeds from splitmix64(s + i)); ``reset()`` resets every row with the
    next seed of its sequence. ``step(actions)`` with actions (num_envs, action size) returns
    ``(obs, rewards, terminations, truncations, infos)``: obs a dict of (num_envs, *shape) arrays
    (or (num_envs, size) flattened), the others (num_envs,) arrays, and the "next step"
    autoreset (a row reset by this step has reward 0 and neither flag set; ``infos['first']``
    marks those rows)."""

    metadata = {"render_modes": [], "autoreset_mode": "next_step"}
    render_mode = None

    def __init__(self, task, num_envs, threads=1, flatten=False, options=None, **overrides):
        self._args = (task, num_envs, threads, options, overrides)
        self.env = _mjarm.VectorEnvironment(task, num_envs, threads, options, **overrides)
        self.num_envs = num_envs
        self.flatten = flatten
        specs = self.env.observation_spec()
        self.single_action_space = _box(self.env.action_spec())
        self.action_space = _box(self.env.action_spec(), num_envs)
        if flatten:
            self.single_observation_space = _flat_box(specs)
            self.observation_space = _flat_box(specs, num_envs)
        else:
            self.single_observation_space = Dict({n: _box(s) for n, s in specs.items()})
            self.observation_space = Dict({n: _box(s, num_envs) for n, s in specs.items()})

    def _obs(self, batch):
        return batch.values if self.flatten else batch.observation

    @staticmethod
    def _infos(batch):
        return {"discount": batch.discount, "end": batch.end, "first": batch.first()}

    def reset(self, *, seed=None, options=None):
        """Resets every row: ``(obs, infos)``."""
        if options:
            raise ValueError(f"GymVectorEnv.reset: no reset options are supported, got {options!r}")
        if seed is not None:
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

    def close(self):
        """Closes the environments (nothing to release)."""

    def __repr__(self):
        return f"GymVectorEnv({self.env.task!r}, num_envs={self.num_envs})"
