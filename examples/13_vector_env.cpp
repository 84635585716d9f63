// 13_vector_env: a vectorized rollout. Eight reach environments stepped together on two threads,
// with automatic resets: the observations and rewards of the batch come back as contiguous
// arrays (row i for environment i), and the same batch on one thread gives the same arrays bit
// for bit.

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "mjarm/env/vector_environment.hpp"

namespace {

struct Rollout {
  std::vector<double> observations, rewards;
  int episodes = 0;
};

Rollout rollout(int threads) {
  mjarm::EnvironmentOptions options;
  options.time_limit = 0.5;  // 25 steps: several episodes per environment in the rollout
  options.seed = 42;
  mjarm::VectorEnvironment batch("reach", options, 8, threads);
  const mjarm::ArraySpec& spec = batch.action_spec();
  const std::size_t width = static_cast<std::size_t>(spec.size());
  std::vector<double> actions(width * static_cast<std::size_t>(batch.size()));
  std::mt19937_64 rng(1);
  Rollout r;
  batch.reset();
  for (int k = 0; k < 100; ++k) {
    for (std::size_t i = 0; i < actions.size(); ++i) {
      const auto j = static_cast<Eigen::Index>(i % width);
      actions[i] = mjarm::EpisodeRandom::uniform(rng, spec.minimum[j], spec.maximum[j]);
    }
    batch.step(actions);  // an environment whose last step was LAST is reset instead
    for (mjarm::StepType type : batch.step_types()) r.episodes += type == mjarm::StepType::last;
  }
  r.observations.assign(batch.observations().begin(), batch.observations().end());
  r.rewards.assign(batch.rewards().begin(), batch.rewards().end());
  std::printf("%d thread(s): %d episodes ended; rewards of the last step:", threads, r.episodes);
  for (double reward : r.rewards) std::printf(" %.3f", reward);  // NaN: a FIRST row
  std::printf("\n");
  return r;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

int main() {
  const Rollout two = rollout(2);
  const Rollout one = rollout(1);
  const bool same = same_bits(two.observations, one.observations) &&
                    same_bits(two.rewards, one.rewards) && two.episodes == one.episodes;
  std::printf("observations %zu values (8 rows), identical on 1 and 2 threads: %s\n",
              two.observations.size(), same ? "yes" : "no");
  return same && two.episodes > 0 ? 0 : 1;
}
