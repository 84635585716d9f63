#pragma once
// Shared helpers of the dynamics tests: the robots they run on and random states.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::test {

/// A bundled robot and the frame its chain ends at.
struct ArmCase {
  const char* robot;
  const char* frame;
};

/// The arms every dynamics identity is checked on.
inline const std::vector<ArmCase>& dynamics_arms() {
  static const std::vector<ArmCase> arms = {
      {"panda", "attachment_site"}, {"iiwa14", "attachment_site"}, {"ur5e", "attachment_site"},
      {"planar2", "tip"}};
  return arms;
}

/// Joint values drawn uniformly inside the chain's limits (±3 for unlimited joints).
inline Eigen::VectorXd random_q(const Chain& chain, std::mt19937& rng) {
  Eigen::VectorXd q(chain.size());
  for (int i = 0; i < chain.size(); ++i) {
    const double lo = std::isfinite(chain.lower()[i]) ? chain.lower()[i] : -3.0;
    const double hi = std::isfinite(chain.upper()[i]) ? chain.upper()[i] : 3.0;
    q[i] = std::uniform_real_distribution<double>(lo, hi)(rng);
  }
  return q;
}

/// Puts a random chain configuration and a random velocity on every dof (±@p speed) into @p d,
/// then runs mj_forward.
inline void random_state(const Chain& chain, mjData* d, std::mt19937& rng, double speed = 2.0) {
  const mjModel& m = chain.robot().model();
  chain.scatter(random_q(chain, rng), d->qpos);
  std::uniform_real_distribution<double> u(-speed, speed);
  for (int i = 0; i < m.nv; ++i) d->qvel[i] = u(rng);
  mj_forward(&m, d);
}

/// The raw bytes of an mjData (main buffer, then the arena's used part: what mj_forward left in
/// it), to prove that nothing wrote to it.
inline std::vector<unsigned char> data_bytes(const mjData* d) {
  const std::size_t buffer = static_cast<std::size_t>(d->nbuffer);
  const std::size_t arena = d->parena;
  std::vector<unsigned char> bytes(buffer + arena);
  std::memcpy(bytes.data(), d->buffer, buffer);
  std::memcpy(bytes.data() + buffer, d->arena, arena);
  return bytes;
}

}  // namespace mjarm::test
