"""A learning task written in Python, run by mjarm's C++ environment: bring the tool of a UR5e
(built from its DH table) to a random point near its start with a 3-D velocity command that the
task maps onto the environment's end-effector velocity space. A random policy runs for a few
hundred steps; then a proportional policy's gain is tuned by a short random search over the same
number of steps, and both are compared on the same ten seeds.
Exits 0 when the tuned policy does better than the random one."""
import numpy as np

import mjarm

PI = np.pi
rows = [dict(d=0.1625, alpha=PI / 2), dict(a=-0.425), dict(a=-0.3922),
        dict(d=0.1333, alpha=PI / 2), dict(d=0.0997, alpha=-PI / 2), dict(d=0.0996)]
robot = mjarm.dh_robot(mjarm.DhArm(name="ur5e_dh", links=[mjarm.DhLink(**r) for r in rows],
                                   actuators=mjarm.DhActuators.motor, effort=150.0, damping=0.5))
home = np.array([0.0, -1.2, 1.4, -1.8, -1.57, 0.0])
start = mjarm.forward_kinematics(mjarm.Chain(robot, "end"), home).p


class Reach(mjarm.EnvTask):
    name = "py_reach"
    description = "tool to a random point within 10 cm, by velocity"

    def __init__(self):
        super().__init__(robot, "end")
        self.target = start

    def action_spec(self):
        return mjarm.ArraySpec("velocity", [3], [-0.25] * 3, [0.25] * 3)

    def map_action(self, context, action):
        return np.concatenate([action, np.zeros(3)])  # ee_velocities is [v; w]

    def initialize_episode(self, sim, rng):
        sim.reset()
        sim.set_state(home, np.zeros(6))
        self.target = start + rng.uniform(-0.1, 0.1, 3)

    def observation_specs(self):
        return [mjarm.ArraySpec("error", [3])]

    def default_observations(self):
        return ["error", "joint_velocities"]

    def observe(self, name, context):
        return self.target - context.X_WE.p

    def reward(self, context):
        return -float(np.linalg.norm(context.X_WE.p - self.target))

    def terminated(self, context):
        return np.linalg.norm(context.X_WE.p - self.target) < 0.01


env = mjarm.Environment(Reach(), action_space="ee_velocities", time_limit=1.0)
rng = np.random.default_rng(0)


def episode_return(policy, seed):
    ts, total = env.reset(seed=seed), 0.0
    while not ts.last():
        ts = env.step(policy(ts))
        total += ts.reward
    return total


# a random policy, a few hundred steps
steps, returns, ts, total = 0, [], env.reset(seed=100), 0.0
while steps < 300:
    ts = env.step(rng.uniform(-0.25, 0.25, 3))
    total += ts.reward
    steps += 1
    if ts.last():
        returns.append(total)
        ts, total = env.reset(), 0.0
print(f"random policy: {steps} steps, {len(returns)} episodes, mean return {np.mean(returns):.3f}")

# a proportional policy's gain by random search, about as many steps
gain, best = 0.5, episode_return(lambda ts: np.clip(0.5 * ts.observation["error"], -0.25, 0.25), 1)
for trial in range(6):
    g = gain * np.exp(rng.normal(0.0, 0.7))
    r = episode_return(lambda ts: np.clip(g * ts.observation["error"], -0.25, 0.25), 1)
    if r > best:
        gain, best = g, r
print(f"tuned gain {gain:.2f} (return {best:.3f} on the tuning seed)")

seeds = range(200, 210)
random_mean = np.mean([episode_return(lambda ts: rng.uniform(-0.25, 0.25, 3), s) for s in seeds])
tuned_mean = np.mean([episode_return(
    lambda ts: np.clip(gain * ts.observation["error"], -0.25, 0.25), s) for s in seeds])
print(f"on ten new seeds: random {random_mean:.3f}, tuned {tuned_mean:.3f} (mean return)")
raise SystemExit(0 if tuned_mean > random_mean else 1)
