// 12_env_random_policy: the environment loop of a learning agent, with a random policy. The
// reach task on the Panda, end-effector pose deltas (the differential-IK QP and the
// operational-space controller carry them out, 10 physics steps per control step): reset to a
// FIRST time step, step until LAST, sum the rewards. Then the same seed and actions again, to
// show the episode repeats bit for bit; and a proportional policy, which reaches the target.

#include <cstdio>
#include <random>
#include <vector>

#include "mjarm/env/environment.hpp"

int main() {
  mjarm::EnvironmentOptions options;  // ee_pose_deltas, T = 20 ms, 10 s episodes
  options.time_limit = 2.0;
  mjarm::Environment env("reach", options);
  const mjarm::ArraySpec& spec = env.action_spec();
  std::printf("action: %s\n", spec.describe().c_str());
  for (const mjarm::ArraySpec& a : env.observation_spec().arrays())
    std::printf("observation %s\n", a.describe().c_str());

  // a random policy: uniform within the action bounds
  auto episode = [&](std::uint64_t seed, std::vector<double>& last_observation) {
    std::mt19937_64 rng(seed);
    std::vector<double> action(static_cast<std::size_t>(spec.size()));
    mjarm::TimeStep ts = env.reset(seed);
    double episode_return = 0.0;
    int steps = 0;
    while (!ts.last()) {
      for (std::size_t i = 0; i < action.size(); ++i) {
        const auto j = static_cast<Eigen::Index>(i);
        action[i] = mjarm::EpisodeRandom::uniform(rng, spec.minimum[j], spec.maximum[j]);
      }
      ts = env.step(action);
      episode_return += *ts.reward;
      ++steps;
    }
    last_observation.assign(ts.observation.values().begin(), ts.observation.values().end());
    std::printf("seed %llu: %d steps, return %.3f, ended %s (discount %.0f)\n",
                static_cast<unsigned long long>(seed), steps, episode_return, to_string(ts.end),
                *ts.discount);
    return episode_return;
  };
  std::vector<double> first, again;
  const double r1 = episode(7, first);
  const double r2 = episode(7, again);
  const bool repeated = r1 == r2 && first == again;
  std::printf("same seed and actions, same episode bit for bit: %s\n", repeated ? "yes" : "no");

  // a proportional policy on the target offset (gain 0.3: the action moves a goal the arm
  // follows about two steps behind) reaches the target and terminates the episode
  mjarm::TimeStep ts = env.reset(7);
  int steps = 0;
  while (!ts.last()) {
    const std::span<const double> offset = ts.observation["target_offset"];
    ts = env.step(std::vector<double>{0.3 * offset[0], 0.3 * offset[1], 0.3 * offset[2], 0, 0, 0});
    ++steps;
  }
  std::printf("proportional policy: %s after %d steps, distance %.4f m\n", to_string(ts.end), steps,
              -*ts.reward);
  return repeated && ts.end == mjarm::EpisodeEnd::terminated ? 0 : 1;
}
