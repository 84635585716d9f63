"""dm_env adapter of mjarm's environments: ``DmEnv`` is a ``dm_env.Environment`` (needs the
dm-env package, pinned in python/requirements.txt).

``mjarm.Environment`` already has dm_env's interface in C++ types (its ``TimeStep``,
``StepType`` and ``ArraySpec``); this adapter gives the same episodes in dm_env's own types and
with its whole contract, so that code written against ``dm_env`` (and
``dm_env.test_utils.EnvironmentTestMixin``) takes them unchanged:

- ``reset()`` and ``step(action)`` return ``dm_env.TimeStep`` namedtuples with a
  ``dm_env.StepType``; the observation is the time step's own dict of float64 arrays;
- ``step(action)`` on a fresh environment, or after a LAST step, starts a new episode and returns
  its FIRST step, ignoring the action (dm_env's rule; ``mjarm.Environment`` refuses such a step
  instead, so that a forgotten reset is not silent);
- specs are ``dm_env.specs.BoundedArray`` where some bound is finite, ``dm_env.specs.Array``
  where none is.
"""
import dm_env
import numpy as np
from dm_env import specs

from . import _mjarm

__all__ = ["DmEnv"]


def _spec(spec):
    shape = tuple(spec.shape)
    if np.isfinite(spec.minimum).any() or np.isfinite(spec.maximum).any():
        return specs.BoundedArray(shape, spec.dtype, spec.minimum, spec.maximum, spec.name)
    return specs.Array(shape, spec.dtype, spec.name)


class DmEnv(dm_env.Environment):
    """A ``dm_env.Environment`` on :class:`mjarm.Environment`: ``DmEnv(task, options=None,
    **overrides)`` takes the arguments of ``mjarm.Environment`` (or ``env=`` an existing one).
    ``reset(seed=None)`` as ``Environment.reset`` (None: the next seed of the environment's own
    sequence). The wrapped environment is ``env``."""

    def __init__(self, task=None, options=None, env=None, **overrides):
        if env is None:
            if task is None:
                raise TypeError("DmEnv: give a task name or env=")
            env = _mjarm.Environment(task, options, **overrides)
        elif task is not None or options is not None or overrides:
            raise TypeError("DmEnv: give either env= or a task with options, not both")
        self.env = env
        self._action_spec = _spec(env.action_spec())
        self._observation_spec = {name: _spec(s) for name, s in env.observation_spec().items()}
        self._needs_reset = True

    @staticmethod
    def _time_step(ts):
        return dm_env.TimeStep(dm_env.StepType(int(ts.step_type)), ts.reward, ts.discount,
                               ts.observation)

    def reset(self, seed=None):
        """Starts an episode: its FIRST ``dm_env.TimeStep``."""
        ts = self.env.reset(seed)
        self._needs_reset = False
        return self._time_step(ts)

    def step(self, action):
        """One step with ``action``; on a fresh environment or after LAST, a new episode's FIRST
        step (the action is not used)."""
        if self._needs_reset:
            return self.reset()
        ts = self.env.step(action)
        self._needs_reset = ts.last()
        return self._time_step(ts)

    def action_spec(self):
        return self._action_spec

    def observation_spec(self):
        """dict name -> spec, in the observation's order."""
        return dict(self._observation_spec)

    def close(self):
        self.env.close()

    def __repr__(self):
        return f"DmEnv({self.env.task!r})"
