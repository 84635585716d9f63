"""A vectorized rollout: eight reach environments stepped together on two threads with
automatic resets; the observations, rewards and step types of the batch come back as contiguous
NumPy arrays (row i for environment i), and the same rollout on one thread gives the same arrays
bit for bit. Exits 0 when it does."""
import time

import numpy as np

import mjarm

STEP_TYPE_LAST = int(mjarm.StepType.LAST)


def rollout(threads, steps=100):
    # 25 steps an episode: every environment runs several episodes
    batch = mjarm.VectorEnvironment("reach", 8, threads, time_limit=0.5, seed=42)
    spec = batch.action_spec()
    rng = np.random.default_rng(1)
    ts = batch.reset()
    episodes, returns = 0, np.zeros(8)
    start = time.perf_counter()
    for _ in range(steps):
        actions = rng.uniform(spec.minimum, spec.maximum, size=(8,) + spec.shape)
        ts = batch.step(actions)  # a row whose last step was LAST is reset instead (FIRST)
        returns += np.nan_to_num(ts.reward)  # NaN on FIRST rows: dm_env's "no reward"
        episodes += int(np.count_nonzero(ts.step_type == STEP_TYPE_LAST))
    rate = 8 * steps / (time.perf_counter() - start)
    print(f"{threads} thread(s): {episodes} episodes ended, {rate:.0f} environment steps/s; "
          f"mean return per environment {returns.mean():.3f}")
    return ts, episodes


two, episodes_two = rollout(2)
one, episodes_one = rollout(1)
print(f"observations {two.values.shape} (contiguous: {two.values.flags.c_contiguous}), "
      f"ee_pose {two.observation['ee_pose'].shape}")
same = (two.values.tobytes() == one.values.tobytes() and two.reward.tobytes() == one.reward.tobytes()
        and episodes_two == episodes_one)
print(f"identical on 1 and 2 threads: {same}")
raise SystemExit(0 if same and episodes_two > 0 else 1)
