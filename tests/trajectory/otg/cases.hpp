#pragma once
// Seeded random one-DoF cases for the jerk-limited tests: limits, and start and target states
// inside them (startable and reachable, see otg/brake.hpp).

#include <algorithm>
#include <cmath>

#include "mjarm/random.hpp"
#include "mjarm/trajectory/otg/brake.hpp"

namespace mjarm::test {

/// Limits, start and target of one DoF.
struct JerkCase {
  JerkLimits limits;
  KinematicState start, target;
};

/// Draws JerkCase values; a fifth of the states at rest.
class JerkCaseGenerator {
 public:
  explicit JerkCaseGenerator(std::uint64_t seed) : rng_(seed) {}

  JerkCase next() {
    JerkCase c;
    c.limits = {scale(0.2, 4.0), scale(0.3, 8.0), scale(0.5, 40.0)};
    do c.start = state(c.limits);
    while (!is_startable(c.start, c.limits));
    do c.target = state(c.limits);
    while (!is_reachable(c.target, c.limits));
    return c;
  }

  Random& rng() { return rng_; }

 private:
  double scale(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }
  KinematicState state(const JerkLimits& l) {
    KinematicState s{6.0 * unit() - 3.0, l.velocity * (2.0 * unit() - 1.0),
                     l.acceleration * (2.0 * unit() - 1.0)};
    if (unit() < 0.2) s.v = s.a = 0.0;
    return s;
  }
  double unit() { return uniform(rng_); }
  Random rng_;
};

/// Largest of |Δp|, |Δv|, |Δa| between the end of @p p and @p target.
inline double target_error(const JerkProfile& p, const KinematicState& target) {
  const KinematicState e = p.end();
  return std::max({std::abs(e.p - target.p), std::abs(e.v - target.v), std::abs(e.a - target.a)});
}

}  // namespace mjarm::test
