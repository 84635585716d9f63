#include "mjarm/env/env_task.hpp"

#include "mjarm/tasks/shelf_pick_plan.hpp"

namespace mjarm {

std::uint64_t splitmix64(std::uint64_t x) noexcept {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

void EpisodeRandom::reseed(std::uint64_t value) noexcept {
  seed = value;
  task.seed(value);
  randomization.seed(splitmix64(value));
}

double EpisodeRandom::uniform(std::mt19937_64& rng, double lo, double hi) noexcept {
  return lo + (hi - lo) * unit_draw(rng());
}

std::vector<std::string> EnvTask::default_observations() const {
  std::vector<std::string> names{"joint_positions", "joint_velocities", "ee_pose"};
  for (const ArraySpec& spec : observation_specs()) names.push_back(spec.name);
  return names;
}

void EnvTask::before_step(const StepContext&, std::span<const double>) noexcept {}

void EnvTask::after_step(const StepContext&) noexcept {}

void EnvTask::observe(int, const StepContext&, std::span<double> out) const noexcept {
  for (double& v : out) v = 0.0;
}

bool EnvTask::terminated(const StepContext&) const noexcept { return false; }

}  // namespace mjarm
