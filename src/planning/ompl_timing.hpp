#pragma once
// The timing of an OMPL path (until the time-parameterization of the part 1 lands): a
// `JointSpline` through the knots, blended by the slope heuristic, or stopping at every knot
// (straight joint-space segments: exactly the motions the validator checked) when the blended
// curve touches something; every sample checked by a `ConfigurationChecker`.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mjarm/planning/configuration_check.hpp"
#include "mjarm/planning/joint_limits.hpp"
#include "mjarm/planning/joint_spline.hpp"

namespace mjarm::ompl_detail {

struct TimedPath {
  bool ok = false;
  JointSpline trajectory;
  std::int64_t samples = 0;  ///< states checked (both timings)
  std::string message;       ///< the failing sample of the rest-to-rest timing
};

/// @param sample_step largest joint motion between two checked samples [rad]
/// @throws Error when the trajectory would need more than 10⁷ samples (limits out of proportion).
TimedPath time_path(const std::vector<Eigen::VectorXd>& knots, const JointLimits& limits,
                    double sample_step, ConfigurationChecker& checker);

}  // namespace mjarm::ompl_detail
