#include "planning/ompl_timing.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/trajectory/path/joint_path.hpp"
#include "mjarm/trajectory/trajectory_sample.hpp"

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

namespace {

/// TOPP-RA exceeds its limits between grid points by the discretization error (≤ 1.9 % at
/// N = 400 on 10⁴ random paths, docs/trajectory.md): it is given limits this much lower, and on a
/// path where that is not enough, lower still on a finer grid.
constexpr double kToppLimitScale = 0.97;
constexpr int kToppGridIntervals = 400;
constexpr int kToppAttempts = 6;

/// What a checked sample of a time-optimal path met first.
enum class SampleFailure { none, limits, state };

/// The knots with the midpoint of every segment inserted.
std::vector<Eigen::VectorXd> densified(const std::vector<Eigen::VectorXd>& knots) {
  std::vector<Eigen::VectorXd> out;
  out.reserve(2 * knots.size());
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    out.push_back(knots[k]);
    out.push_back(0.5 * (knots[k] + knots[k + 1]));
  }
  out.push_back(knots.back());
  return out;
}

/// Checks every sample of @p path (every joint within its v and a; touching nothing), at most
/// @p spacing apart in time; false at the first failing one (described in @p message).
SampleFailure check_samples(const TimeOptimalPath& path, const JointLimits& limits, double spacing,
                            ConfigurationChecker& checker, std::int64_t& samples,
                            std::string& message) {
  const double intervals = std::ceil(path.duration() / spacing);
  if (!(intervals < kMaxTrajectorySamples)) {
    message = "the time-optimal path would need more than 10^7 samples";
    return SampleFailure::limits;
  }
  const auto m = std::max<std::int64_t>(1, static_cast<std::int64_t>(intervals));
  TrajectorySample sample(path.dofs());
  for (std::int64_t j = 0; j <= m; ++j) {
    const double t = path.duration() * static_cast<double>(j) / static_cast<double>(m);
    path.at(t, sample);
    ++samples;
    if (((sample.velocity.array().abs() - limits.max_velocity.array()) > 1e-9).any() ||
        ((sample.acceleration.array().abs() - limits.max_acceleration.array()) > 1e-9).any()) {
      message = "at t = " + number_text(t) + " s the time-optimal path exceeds a joint limit";
      return SampleFailure::limits;
    }
    const ConfigurationCheck& c = checker.check(sample.position);
    if (!c.ok()) {
      message = "at t = " + number_text(t) + " s of the time-optimal path: " + checker.describe(c);
      return SampleFailure::state;
    }
  }
  return SampleFailure::none;
}

}  // namespace

std::optional<TimeOptimalPath> time_optimally(const std::vector<Eigen::VectorXd>& knots,
                                              const JointLimits& limits, double sample_step,
                                              ConfigurationChecker& checker, std::int64_t& samples,
                                              std::string& message) {
  const double spacing = sample_step / limits.max_velocity.maxCoeff();
  ToppOptions topp;
  topp.grid_intervals = kToppGridIntervals;
  double scale = kToppLimitScale;
  std::vector<Eigen::VectorXd> through = knots;
  for (int attempt = 0; attempt < kToppAttempts; ++attempt) {
    TimeOptimalPath path(JointPath(through), scale * limits.max_velocity,
                         scale * limits.max_acceleration, topp);
    if (!path.solved()) {
      message = "the time-optimal parameterization found no profile";
      return std::nullopt;
    }
    switch (check_samples(path, limits, spacing, checker, samples, message)) {
      case SampleFailure::none:
        return path;
      case SampleFailure::limits:  // the discretization error: a finer grid, lower limits
        topp.grid_intervals *= 2;
        scale *= 0.92;
        break;
      case SampleFailure::state:  // the spline cut a corner: closer to the straight motions
        through = densified(through);
        break;
    }
  }
  return std::nullopt;
}

}  // namespace mjarm::ompl_detail
