#pragma once
// The joint space of a chain as OMPL sees it (private to the planning room's OMPL files, the only
// ones compiled with OMPL's headers): a bounded real vector space with samplers seeded from the
// plan's seed, and MuJoCo's collision check as OMPL's state validity checker.

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include <Eigen/Core>
#include <cstdint>
#include <mutex>

#include "mjarm/planning/collision_checker.hpp"

namespace mjarm::ompl_detail {

/// OMPL's 32-bit seed for the @p index-th generator of a plan seeded with @p seed.
std::uint_fast32_t generator_seed(std::uint64_t seed, std::uint64_t index) noexcept;

/// `CollisionChecker::valid` behind a mutex: PRM judges states on two threads.
class MujocoValidityChecker : public ompl::base::StateValidityChecker {
 public:
  MujocoValidityChecker(const ompl::base::SpaceInformationPtr& si, CollisionChecker& checker);
  bool isValid(const ompl::base::State* state) const override;

 private:
  CollisionChecker& checker_;
  mutable std::mutex mutex_;
};

/// The space of the chain's joints (bounds: the joint ranges; ±π for an unlimited joint), its
/// samplers seeded by @p seed in the order OMPL makes them, @p checker as validity checker and
/// the discrete motion validator every @p resolution [rad] of Euclidean joint distance.
ompl::base::SpaceInformationPtr make_space_information(CollisionChecker& checker, double resolution,
                                                       std::uint64_t seed);

/// Copies q into an OMPL state of the space (n values).
void copy_to_state(const Eigen::VectorXd& q, ompl::base::State* state);
/// The n values of an OMPL state.
Eigen::VectorXd state_values(const ompl::base::State* state, int n);

}  // namespace mjarm::ompl_detail
