#pragma once
// Seeded random joint configurations for tests: uniform inside a chain's limits, and normal
// perturbations of a configuration. Any standard random engine (std::mt19937, std::mt19937_64);
// the same engine and seed give the same configurations, bit for bit.

#include <Eigen/Core>
#include <cmath>
#include <random>

#include "mjarm/model/chain.hpp"

namespace mjarm::test {

/// Uniform joint values inside the limits shrunk by @p margin (a fraction of each range) at
/// each end; unlimited joints are drawn from [−3.14159, 3.14159]. With margin 0 this is
/// lower + u·(upper − lower), u uniform in [0, 1).
template <class Rng>
Eigen::VectorXd random_q(const Chain& chain, Rng& rng, double margin = 0.0) {
  Eigen::VectorXd q(chain.size());
  for (int i = 0; i < chain.size(); ++i) {
    const double lo = std::isfinite(chain.lower()[i]) ? chain.lower()[i] : -3.14159;
    const double hi = std::isfinite(chain.upper()[i]) ? chain.upper()[i] : 3.14159;
    const double m = margin * (hi - lo);
    q[i] = std::uniform_real_distribution<double>(lo + m, hi - m)(rng);
  }
  return q;
}

/// @p q moved by a normal perturbation of @p sigma per joint [rad or m], clipped into the
/// limits.
template <class Rng>
Eigen::VectorXd perturb(const Chain& chain, const Eigen::VectorXd& q, Rng& rng, double sigma) {
  std::normal_distribution<double> noise(0.0, sigma);
  Eigen::VectorXd out = q;
  for (int i = 0; i < chain.size(); ++i) out[i] += noise(rng);
  return chain.clamp(out);
}

}  // namespace mjarm::test
