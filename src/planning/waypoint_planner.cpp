#include "mjarm/planning/waypoint_planner.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjarm/trajectory/quintic_duration.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

void check(const PlanOptions& o) {
  check_fields(o);
  check(o.checks);
  check(o.ik);
  check(o.ompl);
}

namespace {

QuinticTrajectory::State rest_state(const Eigen::VectorXd& q) {
  return {q, Eigen::VectorXd::Zero(q.size()), Eigen::VectorXd::Zero(q.size())};
}

bool is_rotation(const Eigen::Matrix3d& R) {
  return R.allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
         R.determinant() > 0.0;
}

PlanStatus status_of(CheckFailure failure) {
  switch (failure) {
    case CheckFailure::joint_limits:
      return PlanStatus::joint_limits;
    case CheckFailure::collision:
      return PlanStatus::collision;
    case CheckFailure::singular:
      return PlanStatus::singular;
    case CheckFailure::torque:
      return PlanStatus::torque;
    case CheckFailure::none:
    case CheckFailure::invalid:
      break;
  }
  return PlanStatus::unreachable;
}

/// Where the segment that arrives at waypoint @p k starts.
std::string where(int k) {
  return k == 0 ? std::string("the start") : "waypoint " + std::to_string(k - 1);
}

}  // namespace

WaypointPlanner::WaypointPlanner(const Chain& chain, const PlanOptions& options)
    : chain_(chain), options_(options) {
  check(options_);
  const int n = chain_.size();
  const auto fits = [n](const Eigen::VectorXd& v) { return v.size() == 0 || v.size() == n; };
  if (!fits(options_.limits.max_velocity) || !fits(options_.limits.max_acceleration) ||
      !fits(options_.limits.max_torque))
    throw Error("waypoint planner: each limit vector needs " + std::to_string(n) +
                " entries (one per chain joint) or none (from the model)");
  const mjModel& m = chain_.robot().model();
  fixed_qpos_ = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
  q_ = qd_ = qdd_ = Eigen::VectorXd::Zero(n);
}

void WaypointPlanner::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  chain_.check_qpos(qpos, "fixed qpos");
  fixed_qpos_ = qpos;
}

double WaypointPlanner::sample_spacing() const noexcept {
  return std::min(options_.sample_period, options_.sample_step / limits_.max_velocity.maxCoeff());
}

namespace {

// "checking a segment of 5000 s every 0.01 s would need 500001 samples, beyond the 100000
// samples a segment may have (max_segment_samples); …"
[[noreturn]] void throw_too_many_samples(double duration, double spacing, double needed,
                                         std::int64_t bound, const std::string& what) {
  throw Error("waypoint planner: checking a segment of " + number_text(duration) + " s every " +
              number_text(spacing) + " s would need " +
              std::to_string(static_cast<long long>(std::min(needed, 9e18))) +
              " samples, beyond the " + std::to_string(bound) + " samples " + what +
              "; the limits are out of proportion (very slow velocities or accelerations make "
              "a motion of hours)");
}

}  // namespace

int WaypointPlanner::sample_intervals(double duration) const {
  const double count = std::ceil(duration / sample_spacing());
  if (!(count < static_cast<double>(options_.max_segment_samples)))  // also NaN
    throw_too_many_samples(duration, sample_spacing(), count + 1, options_.max_segment_samples,
                           "a segment may have (max_segment_samples; the plan had checked " +
                               std::to_string(checked_) + " before it)");
  return std::max(1, static_cast<int>(count));
}

void WaypointPlanner::spend_samples(int m, double duration) {
  const std::int64_t total = checked_ + m + 1;
  if (total > options_.max_samples)
    throw_too_many_samples(duration, sample_spacing(), static_cast<double>(total),
                           options_.max_samples,
                           "a plan may check in all (max_samples; this one has checked " +
                               std::to_string(checked_) + ")");
  checked_ = total;
}

WaypointPlanner::SegmentCheck WaypointPlanner::check_rest_segment(const Eigen::VectorXd& a,
                                                                  const Eigen::VectorXd& b) {
  SegmentCheck out;
  const QuinticDuration shortest =
      shortest_quintic_duration(rest_state(a), rest_state(b), limits_.max_velocity,
                                limits_.max_acceleration, options_.min_segment_duration);
  double T = shortest.duration;  // rest to rest is always feasible
  for (int attempt = 0; attempt <= options_.stretch_attempts; ++attempt) {
    const QuinticTrajectory segment(rest_state(a), rest_state(b), T);
    const int m = sample_intervals(T);
    spend_samples(m, T);
    out = SegmentCheck{};
    out.ok = true;
    out.duration = T;
    out.min_sigma = std::numeric_limits<double>::infinity();
    for (int j = 0; j <= m; ++j) {
      const double t = T * j / m;
      segment.at(t, q_, qd_, qdd_);
      const ConfigurationCheck& c = checker_->check(q_, qd_, qdd_);
      out.min_sigma = std::min(out.min_sigma, c.sigma_min);
      out.max_torque_ratio = std::max(out.max_torque_ratio, c.torque_ratio);
      if (!c.ok()) {
        out.ok = false;
        out.failure = c;
        out.time = t;
        break;
      }
    }
    if (out.ok || out.failure.failure != CheckFailure::torque) return out;
    T *= options_.stretch_factor;  // slower: less acceleration, less torque
  }
  return out;
}

bool WaypointPlanner::check_spline_segment(const JointSpline& spline, int k, SegmentCheck& out) {
  const double t0 = spline.knot_time(k);
  const double T = spline.knot_time(k + 1) - t0;
  const int m = sample_intervals(T);
  spend_samples(m, T);
  out = SegmentCheck{};
  out.ok = true;
  out.duration = T;
  out.min_sigma = std::numeric_limits<double>::infinity();
  for (int j = 0; j <= m; ++j) {
    spline.at(t0 + T * j / m, q_, qd_, qdd_);
    const ConfigurationCheck& c = checker_->check(q_, qd_, qdd_);
    out.min_sigma = std::min(out.min_sigma, c.sigma_min);
    out.max_torque_ratio = std::max(out.max_torque_ratio, c.torque_ratio);
    if (!c.ok()) {
      out.ok = false;
      out.failure = c;
      out.time = T * j / m;
      return false;
    }
  }
  return true;
}

PlanResult WaypointPlanner::plan(const Eigen::VectorXd& q_start,
                                 const std::vector<Pose>& waypoints) {
  if (waypoints.empty())
    throw Error("waypoint planner: the path has no waypoint; give at least one pose");
  chain_.check(q_start, "start configuration");
  for (std::size_t k = 0; k < waypoints.size(); ++k) {
    if (!waypoints[k].p.allFinite() || !is_rotation(waypoints[k].R))
      throw Error("waypoint planner: waypoint " + std::to_string(k) +
                  " must have a finite position and a rotation matrix");
  }
  const int n = chain_.size();
  // limits: the user's, the rest from the model at the start
  limits_ = options_.limits;
  if (limits_.max_velocity.size() == 0 || limits_.max_acceleration.size() == 0 ||
      limits_.max_torque.size() == 0) {
    const JointLimits model = joint_limits_from_model(chain_, q_start, options_.model_limits);
    if (limits_.max_velocity.size() == 0) limits_.max_velocity = model.max_velocity;
    if (limits_.max_acceleration.size() == 0) limits_.max_acceleration = model.max_acceleration;
    if (limits_.max_torque.size() == 0) limits_.max_torque = model.max_torque;
  }
  check(limits_, n);
  ConfigurationChecker checker(chain_, limits_, options_.checks);
  checker.set_fixed_qpos(fixed_qpos_);
  checker_ = &checker;
  checked_ = 0;
  rng_.seed(options_.seed);

  PlanResult result;
  result.limits = limits_;
  result.sample_spacing = sample_spacing();
  const ConfigurationCheck& start = checker.check(q_start);
  if (!start.ok()) {
    result.status = PlanStatus::start_failed;
    result.message = "the start configuration fails: " + checker.describe(start);
    return result;
  }

  PoseIk local(chain_, options_.ik);
  local.set_fixed_qpos(fixed_qpos_);
  GlobalIkOptions global_options;
  global_options.max_restarts = 30;
  global_options.timeout = std::chrono::milliseconds(500);
  GlobalIk global(chain_, global_options);
  global.set_fixed_qpos(fixed_qpos_);
  const auto random_offset = [&](double radius) {
    Eigen::VectorXd u(n);
    for (int i = 0; i < n; ++i) u[i] = radius * uniform(rng_, -1.0, 1.0);
    return u;
  };

  std::vector<Eigen::VectorXd> knots{q_start};
  std::vector<double> floors;
  std::vector<char> blend{0};
  std::vector<int> knot_waypoint{-1};  // the waypoint each knot reaches (−1: start or via)
  for (std::size_t w = 0; w < waypoints.size(); ++w) {
    const int k = static_cast<int>(w);
    const Pose& X_WT = waypoints[w];
    const Eigen::VectorXd q_prev = knots.back();
    WaypointReport report;
    report.index = k;
    report.X_WT = X_WT;

    struct Candidate {
      IkResult ik;
      int branch = 0;
    };
    std::vector<Candidate> valid;              // solutions that pass the checks at rest
    std::optional<Candidate> first_converged;  // for the failure message
    std::optional<ConfigurationCheck> first_check;
    std::optional<Candidate> best;  // smallest position error, for unreachable
    std::optional<SegmentCheck> first_segment;
    std::optional<std::pair<Candidate, SegmentCheck>> accepted;
    const auto consider = [&](const IkResult& ik, int branch) {
      const Candidate c{ik, branch};
      if (!best || ik.position_error < best->ik.position_error) best = c;
      if (!ik.ok()) return;
      const ConfigurationCheck& check = checker.check(ik.q);
      if (!first_converged) {
        first_converged = c;
        first_check = check;
      }
      if (!check.ok()) return;
      valid.push_back(c);
      const SegmentCheck segment = check_rest_segment(q_prev, ik.q);
      if (segment.ok) {
        accepted.emplace(c, segment);
      } else if (!first_segment) {
        first_segment = segment;
      }
    };
    consider(local.solve(X_WT, q_prev), 0);
    for (int b = 1; b <= options_.ik_branches && !accepted; ++b) {
      const double radius = options_.branch_spread * b / options_.ik_branches;
      const Eigen::VectorXd seed = chain_.clamp(q_prev + random_offset(radius));
      consider(global.solve(X_WT, seed), b);
    }
    // a joint-space detour to the valid solution closest to the previous knot
    std::optional<Eigen::VectorXd> via;
    if (!accepted && !valid.empty()) {
      const Candidate target = *std::min_element(
          valid.begin(), valid.end(), [&](const Candidate& a, const Candidate& b) {
            return (a.ik.q - q_prev).norm() < (b.ik.q - q_prev).norm();
          });
      const Eigen::VectorXd middle = 0.5 * (q_prev + target.ik.q);
      for (int s = 1; s <= options_.detour_samples && !accepted; ++s) {
        const double radius = options_.detour_radius * s / options_.detour_samples;
        const Eigen::VectorXd q_via = chain_.clamp(middle + random_offset(radius));
        if (!checker.check(q_via).ok()) continue;
        const SegmentCheck first = check_rest_segment(q_prev, q_via);
        if (!first.ok) continue;
        const SegmentCheck second = check_rest_segment(q_via, target.ik.q);
        if (!second.ok) continue;
        via = q_via;
        knots.push_back(q_via);
        floors.push_back(first.duration);
        blend.push_back(1);
        knot_waypoint.push_back(-1);
        accepted.emplace(target, second);
      }
    }
    // the detour failed: OMPL searches the joint space to the closest valid solution
    int ompl_knots = 0;
    std::string ompl_note;
    if (!accepted && !valid.empty() && options_.ompl_fallback) {
      const Candidate target = *std::min_element(
          valid.begin(), valid.end(), [&](const Candidate& a, const Candidate& b) {
            return (a.ik.q - q_prev).norm() < (b.ik.q - q_prev).norm();
          });
      OmplOptions ompl = options_.ompl;
      ompl.seed = options_.seed + static_cast<std::uint64_t>(w);
      ompl.collision_margin = options_.checks.collision_margin;
      OmplPlanner fallback(chain_, ompl);
      fallback.set_fixed_qpos(fixed_qpos_);
      const OmplResult path = fallback.plan(q_prev, JointGoal{target.ik.q});
      // OMPL judged contacts only: every segment passes the full checks too, at rest
      std::vector<SegmentCheck> legs;
      for (std::size_t j = 1; path.ok() && j < path.path.size(); ++j) {
        legs.push_back(check_rest_segment(path.path[j - 1], path.path[j]));
        if (!legs.back().ok) break;
      }
      if (path.ok() && legs.size() + 1 == path.path.size() && legs.back().ok) {
        for (std::size_t j = 1; j + 1 < path.path.size(); ++j) {
          knots.push_back(path.path[j]);
          floors.push_back(legs[j - 1].duration);
          blend.push_back(1);
          knot_waypoint.push_back(-1);
        }
        ompl_knots = static_cast<int>(path.path.size()) - 2;
        accepted.emplace(target, legs.back());
      } else if (path.ok() && !legs.empty()) {
        first_segment = legs.back();  // why the OMPL path was refused
        ompl_note = "; OMPL's path fails the checks";
      } else {
        ompl_note = "; OMPL: " + path.message;
      }
    }
    if (!accepted) {
      const int tried = 1 + options_.ik_branches;
      std::ostringstream why;
      if (!first_converged) {
        result.status = PlanStatus::unreachable;
        report.q = best->ik.q;
        report.ik = best->ik.status;
        report.position_error = best->ik.position_error;
        report.orientation_error = best->ik.orientation_error;
        why << "no IK solution in " << tried << " tries (best: position error "
            << best->ik.position_error << " m, orientation error " << best->ik.orientation_error
            << " rad): outside the workspace?";
      } else if (valid.empty()) {
        result.status = status_of(first_check->failure);
        report.q = first_converged->ik.q;
        report.ik = first_converged->ik.status;
        report.check = *first_check;
        why << "every IK solution fails (" << tried
            << " tries); the first: " << checker.describe(*first_check);
      } else {
        result.status = PlanStatus::blocked;
        report.q = valid.front().ik.q;
        report.ik = valid.front().ik.status;
        why << "the motion from " << where(k) << " fails at t = " << first_segment->time
            << " s of the segment: " << checker.describe(first_segment->failure) << " ("
            << valid.size() << " valid IK solutions, " << options_.detour_samples
            << " detour samples tried" << (options_.ompl_fallback ? ", then OMPL" : "") << ")"
            << ompl_note;
      }
      report.message = why.str();
      result.failed_waypoint = k;
      result.message = "waypoint " + std::to_string(k) + ": " + report.message;
      result.waypoints.push_back(report);
      checker_ = nullptr;
      return result;
    }
    const auto& [chosen, segment] = *accepted;
    report.q = chosen.ik.q;
    report.ik = chosen.ik.status;
    report.position_error = chosen.ik.position_error;
    report.orientation_error = chosen.ik.orientation_error;
    report.branch = chosen.branch;
    report.detour = via.has_value() || ompl_knots > 0;
    report.ompl_knots = ompl_knots;
    report.check = checker.check(chosen.ik.q);
    report.message = "ok";
    result.waypoints.push_back(report);
    knots.push_back(chosen.ik.q);
    floors.push_back(segment.duration);
    blend.push_back(1);
    knot_waypoint.push_back(k);
  }
  blend.back() = 0;

  // the blended trajectory, checked at every sample; a failing segment stops at both its ends
  // (then it is the rest-to-rest segment already checked, with the same duration)
  JointSpline spline =
      JointSpline::timed(knots, limits_.max_velocity, limits_.max_acceleration, floors, blend);
  std::vector<SegmentCheck> segments(floors.size());
  for (int k = 0; k < spline.segments();) {
    result.samples += sample_intervals(spline.knot_time(k + 1) - spline.knot_time(k)) + 1;
    if (check_spline_segment(spline, k, segments[k])) {
      ++k;
      continue;
    }
    if (!blend[k] && !blend[k + 1]) {
      result.status = PlanStatus::blocked;
      result.message = "segment " + std::to_string(k) +
                       " fails at rest: " + checker.describe(segments[k].failure);
      checker_ = nullptr;
      return result;
    }
    blend[k] = blend[k + 1] = 0;
    spline =
        JointSpline::timed(knots, limits_.max_velocity, limits_.max_acceleration, floors, blend);
    k = 0;
  }
  // per waypoint: the figures of the segments that arrive there
  double min_sigma = std::numeric_limits<double>::infinity();
  double max_torque = 0.0;
  for (std::size_t j = 1; j < knots.size(); ++j) {
    min_sigma = std::min(min_sigma, segments[j - 1].min_sigma);
    max_torque = std::max(max_torque, segments[j - 1].max_torque_ratio);
    if (knot_waypoint[j] < 0) continue;
    WaypointReport& report = result.waypoints[knot_waypoint[j]];
    report.min_sigma = min_sigma;
    report.max_torque_ratio = max_torque;
    report.time = spline.knot_time(static_cast<int>(j));
    min_sigma = std::numeric_limits<double>::infinity();
    max_torque = 0.0;
  }
  result.status = PlanStatus::ok;
  result.message = std::to_string(waypoints.size()) + " waypoints in " +
                   number_text(spline.duration()) + " s, " + std::to_string(result.samples) +
                   " samples checked";
  result.trajectory = std::move(spline);
  checker_ = nullptr;
  return result;
}

}  // namespace mjarm
