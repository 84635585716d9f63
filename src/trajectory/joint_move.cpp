#include "mjarm/trajectory/joint_move.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

constexpr std::array<ProfileKindInfo, 5> kProfileKinds{{
    {ProfileKind::trapezoid, to_string(ProfileKind::trapezoid),
     "trapezoidal velocity, every axis finishing together (rest to rest)", false, false, false},
    {ProfileKind::quintic, to_string(ProfileKind::quintic),
     "quintic polynomial, any start and target (p, v, a); shortest duration", true, true, false},
    {ProfileKind::smoothstep, to_string(ProfileKind::smoothstep), "x²(3 − 2x) ramp, C¹ (rest to rest)", false, true,
     false},
    {ProfileKind::smootherstep, to_string(ProfileKind::smootherstep),
     "6x⁵ − 15x⁴ + 10x³ ramp, C², minimum jerk (rest to rest)", false, true, false},
    {ProfileKind::jerk_limited, to_string(ProfileKind::jerk_limited),
     "time-optimal under velocity, acceleration and jerk limits (needs --j-max), any start and "
     "target (p, v, a); a start beyond the limits brakes first",
     true, false, true},
}};

// %.6g, as the command line prints these figures
std::string move_number(double value) { return number_text(value, 6); }

// @p v with n entries: itself, or @p fill when empty
Eigen::VectorXd move_entries(const Eigen::VectorXd& v, Eigen::Index n, double fill,
                             const char* what) {
  if (v.size() == 0) return Eigen::VectorXd::Constant(n, fill);
  if (v.size() != n)
    throw Error(std::string("joint move: ") + what + " has " + std::to_string(v.size()) +
                " entries, the start " + std::to_string(n));
  return v;
}

JointMoveRequest checked_move_request(ProfileKind kind, const JointMoveRequest& request) {
  const ProfileKindInfo& info = profile_kind_info(kind);
  const Eigen::Index n = request.start.size();
  if (n == 0) throw Error("joint move: the start has no axes");
  if (request.target.size() != n)
    throw Error("joint move: the target has " + std::to_string(request.target.size()) +
                " entries, the start " + std::to_string(n));
  JointMoveRequest r;
  r.start = request.start;
  r.target = request.target;
  r.start_velocity = move_entries(request.start_velocity, n, 0.0, "the start velocity");
  r.start_acceleration = move_entries(request.start_acceleration, n, 0.0, "the start acceleration");
  r.target_velocity = move_entries(request.target_velocity, n, 0.0, "the target velocity");
  r.target_acceleration =
      move_entries(request.target_acceleration, n, 0.0, "the target acceleration");
  r.max_velocity = move_entries(request.max_velocity, n, 0.0, "the velocity limit");
  r.max_acceleration = move_entries(request.max_acceleration, n, 0.0, "the acceleration limit");
  r.max_jerk =
      move_entries(request.max_jerk, n, std::numeric_limits<double>::quiet_NaN(), "the jerk limit");
  r.duration = request.duration;
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::string axis = "joint move: axis " + std::to_string(i) + ": ";
    for (const double x : {r.start[i], r.target[i], r.start_velocity[i], r.start_acceleration[i],
                           r.target_velocity[i], r.target_acceleration[i]})
      if (!std::isfinite(x)) throw Error(axis + "the states must be finite, got " + move_number(x));
    for (const double limit : {r.max_velocity[i], r.max_acceleration[i]})
      if (!(limit > 0.0) || !std::isfinite(limit))
        throw Error(axis +
                    "the velocity and acceleration limits must be positive and finite, got " +
                    number_text(r.max_velocity[i]) + " and " + number_text(r.max_acceleration[i]));
    if (!std::isnan(r.max_jerk[i]) && !(r.max_jerk[i] > 0.0))
      throw Error(axis + "the jerk limit must be positive (NaN: none), got " +
                  number_text(r.max_jerk[i]));
  }
  const bool moving = r.start_velocity.any() || r.start_acceleration.any() ||
                      r.target_velocity.any() || r.target_acceleration.any();
  if (moving && !info.moving_ends)
    throw Error(std::string("joint move: ") + info.name +
                " moves from rest to rest; boundary velocities and accelerations need a kind "
                "that takes them (quintic, jerk-limited)");
  if (r.duration && !info.given_duration)
    throw Error(std::string("joint move: ") + info.name +
                " takes the shortest duration within its limits, not a given one");
  if (r.duration && (!(*r.duration > 0.0) || !std::isfinite(*r.duration)))
    throw Error("joint move: the duration must be positive and finite, got " +
                number_text(*r.duration) + " s");
  if (info.jerk_limit && r.max_jerk.hasNaN())
    throw Error(std::string("joint move: ") + info.name + " needs a jerk limit on every axis");
  return r;
}

SyncedTrapezoid plan_trapezoid(const JointMoveRequest& r) {
  return SyncedTrapezoid(r.start, r.target, r.max_velocity, r.max_acceleration);
}

QuinticTrajectory plan_quintic(const JointMoveRequest& r,
                               std::optional<QuinticDuration>& shortest) {
  const QuinticTrajectory::State start{r.start, r.start_velocity, r.start_acceleration};
  const QuinticTrajectory::State end{r.target, r.target_velocity, r.target_acceleration};
  if (r.duration) return QuinticTrajectory(start, end, *r.duration);
  const QuinticDuration d =
      shortest_quintic_duration(start, end, r.max_velocity, r.max_acceleration);
  if (d.status != QuinticDurationStatus::ok)
    throw Error(std::string("no quintic duration keeps the limits: ") + to_string(d.status) +
                (d.limiting_joint >= 0
                     ? " (axis " + std::to_string(d.limiting_joint) + ", " +
                           (d.velocity_limited ? "velocity" : "acceleration") + ")"
                     : std::string()));
  shortest = d;
  return QuinticTrajectory(start, end, d.duration);
}

SmoothRampTrajectory plan_ramp(SmoothRamp::Kind kind, const JointMoveRequest& r) {
  if (r.duration) return SmoothRampTrajectory(kind, r.start, r.target, *r.duration);
  return SmoothRampTrajectory::within_limits(kind, r.start, r.target, r.max_velocity,
                                             r.max_acceleration);
}

JerkLimitedGenerator plan_jerk_limited(const JointMoveRequest& r) {
  const Eigen::Index n = r.start.size();
  std::vector<JerkLimits> limits;
  std::vector<KinematicState> start, target;
  for (Eigen::Index i = 0; i < n; ++i) {
    limits.push_back({r.max_velocity[i], r.max_acceleration[i], r.max_jerk[i]});
    start.push_back({r.start[i], r.start_velocity[i], r.start_acceleration[i]});
    target.push_back({r.target[i], r.target_velocity[i], r.target_acceleration[i]});
  }
  JerkLimitedGenerator otg(limits);
  const OtgResult result = otg.calculate(start, target);  // an unreachable target throws
  if (result.status == OtgStatus::error_precision) {
    std::string check;
    if (result.end_error > OtgResult::kEndTolerance)
      check = "its end misses the target by " + move_number(result.end_error) +
              " relative to the start and target (tolerance " +
              move_number(OtgResult::kEndTolerance) + ")";
    else if (result.limit_excess > OtgResult::kLimitTolerance)
      check = "it exceeds a limit by " + move_number(result.limit_excess) +
              " relative (tolerance " + move_number(OtgResult::kLimitTolerance) + ")";
    else
      check = "an axis's profile lasts " + move_number(result.sync_error) +
              " s more or less than " + move_number(result.duration) + " s";
    throw Error("jerk-limited: no trajectory on axis " + std::to_string(result.failed_dof) +
                " (error_precision): " + check +
                "; limits this far apart make the motion too large for double precision (see "
                "\"Supported limits\" in docs/trajectory_otg.md)");
  }
  if (result.status != OtgStatus::working && result.status != OtgStatus::finished)
    throw Error(std::string("jerk-limited: no trajectory (") + to_string(result.status) +
                (result.failed_dof >= 0 ? ", axis " + std::to_string(result.failed_dof) : "") +
                ")");
  return otg;
}

JointMove::Profile plan_profile(ProfileKind kind, const JointMoveRequest& r,
                                std::optional<QuinticDuration>& shortest) {
  switch (kind) {
    case ProfileKind::trapezoid:
      return plan_trapezoid(r);
    case ProfileKind::quintic:
      return plan_quintic(r, shortest);
    case ProfileKind::smoothstep:
      return plan_ramp(SmoothRamp::Kind::smoothstep, r);
    case ProfileKind::smootherstep:
      return plan_ramp(SmoothRamp::Kind::smootherstep, r);
    case ProfileKind::jerk_limited:
      return plan_jerk_limited(r);
  }
  throw Error("joint move: unknown profile kind " + std::to_string(static_cast<int>(kind)));
}

// the peaks of each profile, exact: at the analytic extrema of its phases
TrajectoryPeaks profile_peaks(const SyncedTrapezoid& move) {
  const auto n = static_cast<Eigen::Index>(move.size());
  TrajectoryPeaks p{Eigen::VectorXd(n), Eigen::VectorXd(n),
                    Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity())};
  for (Eigen::Index i = 0; i < n; ++i) {
    // axis i is its own trapezoid run λ times slower: velocity ×λ, acceleration ×λ²
    const auto k = static_cast<std::size_t>(i);
    const double lambda = move.time_scale(k);
    const TrapezoidProfile& axis = move.axis(k);
    p.velocity[i] = lambda * axis.peak_velocity();
    p.acceleration[i] = axis.distance() > 0.0 ? lambda * lambda * axis.acceleration() : 0.0;
  }
  return p;
}

TrajectoryPeaks profile_peaks(const QuinticTrajectory& traj) {
  const Eigen::Index n = traj.size();
  TrajectoryPeaks p{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    const Quintic::Peaks peaks = traj.joint(i).peaks();
    p.velocity[i] = peaks.velocity;
    p.acceleration[i] = peaks.acceleration;
    p.jerk[i] = peaks.jerk;
  }
  return p;
}

TrajectoryPeaks profile_peaks(const SmoothRampTrajectory& ramp) {
  return {ramp.peak_velocity(), ramp.peak_acceleration(), ramp.peak_jerk()};
}

TrajectoryPeaks profile_peaks(const JerkLimitedGenerator& otg) {
  const Eigen::Index n = otg.dofs();
  TrajectoryPeaks p{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd::Zero(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    const JerkProfile& profile = otg.profile(static_cast<int>(i));
    // velocity and acceleration after the brake (a start beyond the limits is braked into them)
    const JerkExtrema e = profile.extrema(otg.brake_phases(static_cast<int>(i)));
    p.velocity[i] = std::max(std::abs(e.v_min), std::abs(e.v_max));
    p.acceleration[i] = std::max(std::abs(e.a_min), std::abs(e.a_max));
    for (int k = 0; k < profile.size(); ++k)
      if (profile.phase_duration(k) > 0.0)
        p.jerk[i] = std::max(p.jerk[i], std::abs(profile.jerk(k)));
  }
  return p;
}

}  // namespace

const std::array<ProfileKindInfo, 5>& profile_kinds() noexcept { return kProfileKinds; }

const ProfileKindInfo& profile_kind_info(ProfileKind kind) noexcept {
  for (const ProfileKindInfo& info : kProfileKinds)
    if (info.kind == kind) return info;
  return kProfileKinds.front();  // not reached: every kind has a row
}

JointMove::JointMove(ProfileKind kind, const JointMoveRequest& request)
    : kind_(kind),
      request_(checked_move_request(kind, request)),
      profile_(plan_profile(kind, request_, quintic_duration_)) {
  std::visit(
      [this](const auto& profile) {
        duration_ = profile.duration();
        peaks_ = profile_peaks(profile);
      },
      profile_);
  if (const auto* trapezoid = std::get_if<SyncedTrapezoid>(&profile_))
    limiting_axis_ =
        duration_ > 0.0 ? static_cast<Eigen::Index>(trapezoid->limiting_axis()) : Eigen::Index{-1};
  else if (const auto* ramp = std::get_if<SmoothRampTrajectory>(&profile_))
    limiting_axis_ = ramp->limiting_axis();
  else if (quintic_duration_)
    limiting_axis_ = quintic_duration_->limiting_joint;
  else if (const auto* otg = std::get_if<JerkLimitedGenerator>(&profile_))
    limiting_axis_ = otg->result().limiting_dof;
}

void JointMove::at(double t, TrajectorySample& sample) const {
  std::visit([&](const auto& profile) { profile.at(t, sample); }, profile_);
}

std::vector<LimitViolation> JointMove::violations() const {
  std::vector<LimitViolation> out;
  const auto check = [&](Eigen::Index i, LimitViolation::Quantity quantity, double peak,
                         double limit) {
    if (peak > limit * (1 + 1e-9))  // a NaN limit (no jerk limit) is never broken
      out.push_back({i, quantity, peak, limit});
  };
  for (Eigen::Index i = 0; i < dofs(); ++i) {
    check(i, LimitViolation::Quantity::velocity, peaks_.velocity[i], request_.max_velocity[i]);
    check(i, LimitViolation::Quantity::acceleration, peaks_.acceleration[i],
          request_.max_acceleration[i]);
    check(i, LimitViolation::Quantity::jerk, peaks_.jerk[i], request_.max_jerk[i]);
  }
  return out;
}

}  // namespace mjarm
