#pragma once
/// @file
/// `ArmReach`: how near and how far from its shoulder an arm's tool frame can be, for messages
/// that tell a user why a point is out of reach.

#include <Eigen/Core>
#include <cstdint>

#include "mjarm/model/chain.hpp"

namespace mjarm {

/// The shell of distances from an arm's shoulder that its frame reaches within the joint limits.
struct ArmReach {
  /// The shoulder: anchor of the chain's most proximal joint at the centre configuration (world,
  /// m) — the point every reach is measured from.
  Eigen::Vector3d p_WS = Eigen::Vector3d::Zero();
  double min_distance = 0.0;  ///< smallest ‖p_WE − p_WS‖ seen [m]
  double max_distance = 0.0;  ///< largest ‖p_WE − p_WS‖ seen [m]
  int samples = 0;            ///< configurations sampled
};

/// Samples @p samples configurations uniformly within @p chain's limits (a fixed seed: the same
/// shell every time) and returns the range of distances of the frame from the shoulder. Sampled,
/// so the true shell is slightly wider (a few mm at 20 000 samples for a 2- to 7-joint arm):
/// use it to explain a failure, not to decide reachability.
/// @throws Error when @p samples < 1.
ArmReach arm_reach(const Chain& chain, int samples = 20000, std::uint64_t seed = 1);

}  // namespace mjarm
