"""An environment loop with a random policy: the reach task on the panda (end-effector pose
deltas, 20 ms control steps), dm_env's interface first, then the same episodes through the
Gymnasium-style adapter. A seeded random policy gives the same returns on every run; the
policy that moves towards the target must end its episode by termination (within 1 cm).
Exits 0 when both hold."""
import numpy as np

import mjarm
from mjarm.gym import GymEnv

env = mjarm.Environment("reach", time_limit=2.0)
spec = env.action_spec()
rng = np.random.default_rng(0)


def random_policy(time_step):
    return rng.uniform(spec.minimum, spec.maximum)


def towards_target(time_step):
    action = np.zeros(spec.shape)
    action[:3] = 0.3 * time_step.observation["target_offset"]  # gain < 1: the goal integrates
    return action


def episode(policy, seed):
    ts = env.reset(seed)
    ret = 0.0
    while not ts.last():
        ts = env.step(policy(ts))
        ret += ts.reward
    return ret, ts.end, env.steps


print(f"action: {spec.describe()}")
for name, s in env.observation_spec().items():
    print(f"observation {s.describe()}")
for seed in range(3):
    ret, end, steps = episode(random_policy, seed)
    print(f"random policy, seed {seed}: return {ret:8.3f} after {steps} steps ({end.name})")
ret, end, steps = episode(towards_target, 0)
print(f"towards the target, seed 0: return {ret:8.3f} after {steps} steps ({end.name})")
reached = end == mjarm.EpisodeEnd.terminated

# the same with Gymnasium's conventions: (obs, info) and (obs, reward, terminated, truncated, info)
gym = GymEnv("reach", time_limit=2.0)
gym.action_space.seed(0)
returns = []
for seed in (0, 1):
    obs, info = gym.reset(seed=seed)
    total, terminated, truncated = 0.0, False, False
    while not (terminated or truncated):
        obs, reward, terminated, truncated, info = gym.step(gym.action_space.sample())
        total += reward
    returns.append(total)
    print(f"gym adapter, seed {seed}: return {total:8.3f}, terminated {terminated}, "
          f"truncated {truncated}")
# the adapter's sampler, reseeded, replays the same episodes exactly
gym.action_space.seed(0)
again = []
for seed in (0, 1):
    gym.reset(seed=seed)
    total, done = 0.0, False
    while not done:
        _, reward, terminated, truncated, _ = gym.step(gym.action_space.sample())
        total, done = total + reward, terminated or truncated
    again.append(total)
print(f"replayed with the same seeds: identical returns {again == returns}")
raise SystemExit(0 if reached and again == returns else 1)
