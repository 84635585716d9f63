#include "planning/ompl_state_space.hpp"

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "mjarm/random.hpp"

namespace mjarm::ompl_detail {

namespace ob = ompl::base;

std::uint_fast32_t generator_seed(std::uint64_t seed, std::uint64_t index) noexcept {
  // OMPL treats a seed of 0 as "draw one from the clock": never give it 0
  const std::uint64_t mixed = splitmix64(splitmix64(seed) ^ (index + 1));
  const auto seed32 = static_cast<std::uint_fast32_t>(mixed & 0xffffffffu);
  return seed32 == 0 ? 1 : seed32;
}

namespace {

/// OMPL's uniform sampler of the joint box with a generator seeded by the plan, not by OMPL's
/// process-wide seed sequence: the same plan seed gives the same samples on any call.
class SeededJointSampler : public ob::RealVectorStateSampler {
 public:
  SeededJointSampler(const ob::StateSpace* space, std::uint_fast32_t seed)
      : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

}  // namespace

MujocoValidityChecker::MujocoValidityChecker(const ob::SpaceInformationPtr& si,
                                             CollisionChecker& checker)
    : ob::StateValidityChecker(si), checker_(checker) {}

bool MujocoValidityChecker::isValid(const ob::State* state) const {
  const double* q = state->as<ob::RealVectorStateSpace::StateType>()->values;
  const std::lock_guard<std::mutex> lock(mutex_);
  return checker_.valid(q);
}

ob::SpaceInformationPtr make_space_information(CollisionChecker& checker, double resolution,
                                               std::uint64_t seed) {
  const Chain& chain = checker.chain();
  const int n = chain.size();
  auto space = std::make_shared<ob::RealVectorStateSpace>(n);
  ob::RealVectorBounds bounds(n);
  for (int i = 0; i < n; ++i) {
    const double lo = chain.lower()[i];
    const double hi = chain.upper()[i];
    bounds.setLow(i, std::isfinite(lo) ? lo : -std::numbers::pi);
    bounds.setHigh(i, std::isfinite(hi) ? hi : std::numbers::pi);
  }
  space->setBounds(bounds);
  auto made = std::make_shared<std::uint64_t>(0);
  space->setStateSamplerAllocator([seed, made](const ob::StateSpace* s) -> ob::StateSamplerPtr {
    return std::make_shared<SeededJointSampler>(s, generator_seed(seed, (*made)++));
  });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<MujocoValidityChecker>(si, checker));
  // OMPL's resolution is a fraction of the space's extent (the box's diagonal)
  si->setStateValidityCheckingResolution(std::min(1.0, resolution / space->getMaximumExtent()));
  si->setup();
  return si;
}

void copy_to_state(const Eigen::VectorXd& q, ob::State* state) {
  double* values = state->as<ob::RealVectorStateSpace::StateType>()->values;
  for (Eigen::Index i = 0; i < q.size(); ++i) values[i] = q[i];
}

Eigen::VectorXd state_values(const ob::State* state, int n) {
  const double* values = state->as<ob::RealVectorStateSpace::StateType>()->values;
  return Eigen::Map<const Eigen::VectorXd>(values, n);
}

}  // namespace mjarm::ompl_detail
