#pragma once
// The timing of an OMPL path: a `JointSpline` through the knots, blended by the slope heuristic,
// or stopping at every knot (straight joint-space segments: exactly the motions the validator
// checked) when the blended curve touches something; and, when asked, the time-optimal timing of
// the knots' C² spline (TOPP-RA). Every sample of each is checked by a `ConfigurationChecker`.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mjarm/planning/configuration_check.hpp"
#include "mjarm/planning/joint_limits.hpp"
#include "mjarm/planning/joint_spline.hpp"
#include "mjarm/trajectory/path/time_optimal_path.hpp"

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

/// The time-optimal timing of the C² spline through @p knots under @p limits (v, a), or none when
/// six attempts leave a sample beyond the limits or touching something: after a sample beyond
/// the limits the next attempt has a grid twice as fine and limits 8 % lower; after one touching
/// something (or out of a range) the knot spacing is halved, which brings the spline closer to
/// the straight segments the validator checked. @p samples counts the states checked,
/// @p message says why there is none.
std::optional<TimeOptimalPath> time_optimally(const std::vector<Eigen::VectorXd>& knots,
                                              const JointLimits& limits, double sample_step,
                                              ConfigurationChecker& checker, std::int64_t& samples,
                                              std::string& message);

}  // namespace mjarm::ompl_detail
