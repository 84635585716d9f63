#include "planning/ompl_timing.hpp"

#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm::ompl_detail {

namespace {

constexpr double kMinSegmentDuration = 0.05;  // [s], as the waypoint planner's default
constexpr double kMaxTrajectorySamples = 1e7;

/// Checks every sample of @p spline, at most @p sample_step apart in any joint; false at the
/// first failing one (described in @p message).
bool check_samples(const JointSpline& spline, double spacing, ConfigurationChecker& checker,
                   std::int64_t& samples, std::string& message) {
  const Eigen::Index n = spline.size();
  Eigen::VectorXd q(n), qd(n), qdd(n);
  const double intervals = std::ceil(spline.duration() / spacing);
  if (!(intervals < kMaxTrajectorySamples))
    throw Error("OMPL planner: checking a trajectory of " + number_text(spline.duration()) +
                " s every " + number_text(spacing) +
                " s would need more than 10^7 samples; the "
                "limits are out of proportion");
  const auto m = std::max<std::int64_t>(1, static_cast<std::int64_t>(intervals));
  for (std::int64_t j = 0; j <= m; ++j) {
    const double t = spline.duration() * static_cast<double>(j) / static_cast<double>(m);
    spline.at(t, q, qd, qdd);
    ++samples;
    const ConfigurationCheck& c = checker.check(q);
    if (!c.ok()) {
      message = "at t = " + number_text(t) + " s of the timed path: " + checker.describe(c);
      return false;
    }
  }
  return true;
}

}  // namespace

TimedPath time_path(const std::vector<Eigen::VectorXd>& knots, const JointLimits& limits,
                    double sample_step, ConfigurationChecker& checker) {
  TimedPath out;
  const std::size_t K = knots.size() - 1;
  const std::vector<double> floors(K, kMinSegmentDuration);
  // |q̇_i| ≤ v_max,i on every segment: a sample every sample_step / max v_max moves no joint more
  const double spacing = sample_step / limits.max_velocity.maxCoeff();
  for (const bool blended : {true, false}) {
    std::vector<char> blend(K + 1, blended ? 1 : 0);
    blend.front() = blend.back() = 0;
    out.trajectory =
        JointSpline::timed(knots, limits.max_velocity, limits.max_acceleration, floors, blend);
    if (check_samples(out.trajectory, spacing, checker, out.samples, out.message)) {
      out.ok = true;
      out.message.clear();
      return out;
    }
  }
  return out;
}

}  // namespace mjarm::ompl_detail
