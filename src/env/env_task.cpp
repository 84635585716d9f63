#include "mjarm/env/env_task.hpp"

#include <algorithm>

namespace mjarm {

void EpisodeRandom::reseed(std::uint64_t value) noexcept {
  seed = value;
  task.seed(value);
  randomization.seed(splitmix64(value));
}

std::vector<std::string> EnvTask::default_observations() const {
  std::vector<std::string> names{"joint_positions", "joint_velocities", "ee_pose"};
  for (const ArraySpec& spec : observation_specs()) names.push_back(spec.name);
  return names;
}

void EnvTask::map_action(const StepContext&, std::span<const double>,
                         std::span<double> space_action) noexcept {
  std::fill(space_action.begin(), space_action.end(), 0.0);
}

void EnvTask::before_step(const StepContext&, std::span<const double>) noexcept {}

void EnvTask::after_step(const StepContext&) noexcept {}

void EnvTask::observe(int, const StepContext&, std::span<double> out) const noexcept {
  for (double& v : out) v = 0.0;
}

bool EnvTask::terminated(const StepContext&) const noexcept { return false; }

}  // namespace mjarm
