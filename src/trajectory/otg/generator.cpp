#include "mjarm/trajectory/otg/generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/trajectory/otg/brake.hpp"
#include "mjarm/trajectory/otg/fixed_time.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"
#include "mjarm/trajectory/otg/sync.hpp"
#include "mjarm/trajectory/otg/velocity.hpp"
#include "mjarm/trajectory/trajectory_sample.hpp"
#include "trajectory/otg/up.hpp"

namespace mjarm {

namespace {

/// A cheap guess of the minimum duration of one DoF (brake excluded), to pick the DoF whose
/// step 1 comes first: the duration of the profile with a cruise at ±v_max when one is valid (the
/// optimum of most long moves), else the rest-to-rest minimum for the same distance.
double duration_estimate(const jerk_detail::UpPair& up, const JerkLimits& limits) noexcept {
  const double d = up.form[0].d;
  for (const int k : {d >= 0.0 ? 0 : 1, d >= 0.0 ? 1 : 0}) {
    const jerk_detail::CruiseShape& c = up.cruise[k];
    if (!c.valid) continue;
    const double cruise = (up.form[k].d - c.p) / c.v;
    if (cruise >= 0.0) return c.duration + cruise;
  }
  // rest to rest over |d|: jerk only, with a hold at a_max, or with a cruise at v_max
  const double V = limits.velocity, A = limits.acceleration, J = limits.jerk;
  const double D = std::abs(d);
  const double a_peak = std::min(A, std::sqrt(V * J));  // the level reached on the way to v_max
  const double t_acc = a_peak / J + V / a_peak;         // 0 → v_max → 0 acceleration
  if (D >= V * t_acc) return D / V + t_acc;
  if (D <= 2.0 * A * A * A / (J * J)) return 4.0 * std::cbrt(D / (2.0 * J));
  return A / J + std::sqrt(A * A / (J * J) + 4.0 * D / A);
}

/// The limits with the acceleration limit lowered to 3·√(v_max·j_max) when it is above: between
/// a startable start and a reachable target no motion within the velocity and jerk limits has
/// |a| > √6·√(v_max·j_max) (the velocity gained while the acceleration rises and falls at full
/// jerk would pass v_max), so that limit never binds; the solvers' structures with holds at ±a_max
/// would otherwise work with powers of an a_max orders of magnitude beyond the motion's.
JerkLimits binding_limits(const JerkLimits& l) noexcept {
  return {l.velocity, std::min(l.acceleration, 3.0 * std::sqrt(l.velocity * l.jerk)), l.jerk};
}

std::string otg_number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

}  // namespace

JerkLimitedGenerator::JerkLimitedGenerator(std::span<const JerkLimits> limits)
    : limits_(limits.begin(), limits.end()) {
  if (limits_.empty()) throw Error("JerkLimitedGenerator: expected limits for at least one DoF");
  for (std::size_t i = 0; i < limits_.size(); ++i)
    check_fields(limits_[i], "JerkLimitedGenerator: DoF " + std::to_string(i));
  profiles_.resize(limits_.size());
  blocks_.resize(limits_.size());
  reach_.resize(limits_.size());
  targets_.resize(limits_.size());
  estimates_.resize(limits_.size());
  solved_.resize(limits_.size());
  order_.resize(limits_.size());
  problems_.resize(limits_.size());
  brake_durations_.resize(limits_.size());
  brake_phases_.resize(limits_.size());
  after_brake_.resize(limits_.size());
}

void JerkLimitedGenerator::check_states(std::span<const KinematicState> current,
                                        std::span<const KinematicState> target,
                                        bool velocity_interface) const {
  const std::size_t n = limits_.size();
  if (current.size() != n || target.size() != n)
    throw Error("JerkLimitedGenerator: expected " + std::to_string(n) +
                " current and target states, got " + std::to_string(current.size()) + " and " +
                std::to_string(target.size()));
  for (std::size_t i = 0; i < n; ++i) {
    const KinematicState& c = current[i];
    const KinematicState& t = target[i];
    // the message prefix is built only on an error (the check runs at every tick)
    const auto dof = [i] { return "JerkLimitedGenerator: DoF " + std::to_string(i) + ": "; };
    if (!std::isfinite(c.p) || !std::isfinite(c.v) || !std::isfinite(c.a))
      throw Error(dof() + "current state must be finite, got p " + otg_number(c.p) + ", v " +
                  otg_number(c.v) + ", a " + otg_number(c.a));
    if ((!velocity_interface && !std::isfinite(t.p)) || !std::isfinite(t.v) || !std::isfinite(t.a))
      throw Error(dof() + "target state must be finite, got p " + otg_number(t.p) + ", v " +
                  otg_number(t.v) + ", a " + otg_number(t.a));
    const JerkLimits& l = limits_[i];
    if (std::abs(t.v) > l.velocity)
      throw Error(dof() + "target velocity " + otg_number(t.v) + " exceeds its limit " +
                  otg_number(l.velocity));
    if (std::abs(t.a) > l.acceleration)
      throw Error(dof() + "target acceleration " + otg_number(t.a) + " exceeds its limit " +
                  otg_number(l.acceleration));
    if (!velocity_interface && !is_reachable(t, l))
      throw Error(dof() + "target state (v " + otg_number(t.v) + ", a " + otg_number(t.a) +
                  ") cannot be reached without exceeding the velocity limit " +
                  otg_number(l.velocity) + " (|v − a·|a|/(2·jerk)| must be ≤ it)");
  }
}

JerkLimitedGenerator::~JerkLimitedGenerator() = default;
JerkLimitedGenerator::JerkLimitedGenerator(const JerkLimitedGenerator&) = default;
JerkLimitedGenerator::JerkLimitedGenerator(JerkLimitedGenerator&&) noexcept = default;
JerkLimitedGenerator& JerkLimitedGenerator::operator=(const JerkLimitedGenerator&) = default;
JerkLimitedGenerator& JerkLimitedGenerator::operator=(JerkLimitedGenerator&&) noexcept = default;

bool JerkLimitedGenerator::solve_step1(int i) const noexcept {
  solved_[i] = 1;
  return jerk_detail::min_time_profile(problems_[i], after_brake_[i], targets_[i], blocks_[i]);
}

OtgResult JerkLimitedGenerator::calculate(std::span<const KinematicState> current,
                                          std::span<const KinematicState> target) {
  check_states(current, target, false);
  time_ = 0.0;
  result_ = OtgResult{};
  velocity_interface_ = false;
  const int n = dofs();
  // the brakes, and a guess of which DoF is slowest
  int first = 0;
  for (int i = 0; i < n; ++i) {
    targets_[i] = target[i];
    solved_[i] = 0;
    JerkProfile& p = profiles_[i];
    p.reset(current[i]);
    const JerkLimits solve = binding_limits(limits_[i]);
    // a start beyond the limits: the brake after which the whole motion is shortest
    if (!append_optimal_brake(current[i], target[i], limits_[i], solve, p, brake_scratch_)) {
      result_.status = OtgStatus::error_brake;
      result_.failed_dof = i;
      return result_;
    }
    brake_durations_[i] = p.duration();
    brake_phases_[i] = p.size();
    after_brake_[i] = p.end();
    problems_[i].set(after_brake_[i], target[i].p - after_brake_[i].p, target[i].v, target[i].a,
                     solve);
    estimates_[i] = p.duration() + duration_estimate(problems_[i], solve);
    if (estimates_[i] > estimates_[first]) first = i;
  }
  // step 1 for the DoFs that decide the duration only: the one guessed slowest, then every DoF
  // that has no profile of the duration synchronized over those so far (it is slower, or the
  // duration lies in one of its blocked intervals). A duration that every DoF can take and
  // that is the smallest some of them can take is the smallest all can take.
  if (!solve_step1(first)) {
    result_.status = OtgStatus::error_no_profile;
    result_.failed_dof = first;
    return result_;
  }
  // the others in the order of their guesses, slowest first: a DoF that cannot take the
  // duration gets its step 1, and the checks start again at the new duration
  for (int i = 0; i < n; ++i) order_[i] = i;
  std::sort(order_.begin(), order_.end(),
            [this](int a, int b) { return estimates_[a] > estimates_[b]; });
  JerkSync sync;
  if (!synchronize(blocks_, brake_durations_, solved_, sync)) {
    result_.status = OtgStatus::error_synchronization;
    return result_;
  }
  for (int k = 0; k < n; ++k) {
    const int i = order_[k];
    if (solved_[i]) continue;
    const double local = sync.duration - brake_durations_[i];
    if (jerk_detail::reach_range(problems_[i], after_brake_[i].p, local, reach_[i]) &&
        reach_contains(reach_[i], target[i].p))
      continue;
    if (!solve_step1(i)) {
      result_.status = OtgStatus::error_no_profile;
      result_.failed_dof = i;
      return result_;
    }
    if (!synchronize(blocks_, brake_durations_, solved_, sync)) {
      result_.status = OtgStatus::error_synchronization;
      return result_;
    }
    k = -1;  // every check again, at the new duration
  }
  result_.duration = sync.duration;
  result_.limiting_dof = sync.limiting_dof;
  // step 3: the extremal profile of that duration, or a blend of the reachable extremes
  for (int i = 0; i < n; ++i) {
    const double local = sync.duration - brake_durations_[i];
    const JerkPhases* extremal = solved_[i] ? blocks_[i].profile_of(local) : nullptr;
    bool ok = true;
    if (extremal != nullptr) {
      ok = extremal->append_to(profiles_[i]);
    } else {
      if (solved_[i])
        ok = jerk_detail::reach_range(problems_[i], after_brake_[i].p, local, reach_[i]);
      ok = ok && append_blended_profile(reach_[i], target[i], local, profiles_[i]);
    }
    if (!ok) {
      result_.status = OtgStatus::error_synchronization;
      result_.failed_dof = i;
      return result_;
    }
  }
  check_result(current, target);
  return result_;
}

void JerkLimitedGenerator::check_result(std::span<const KinematicState> current,
                                        std::span<const KinematicState> target) noexcept {
  // a profile's end is the blend or the integration of phases computed at the scale of the
  // whole motion (brakes far beyond the limits, reachable ranges of hours): its round-off, about
  // 1e-16 of the largest position involved, is checked here against the scale the caller gave
  const double T = result_.duration;
  const double sync_tolerance = OtgResult::kSyncTolerance * std::max(1.0, T);
  result_.end_error = 0.0;
  result_.limit_excess = -1.0;
  result_.sync_error = 0.0;
  int failed = -1;
  for (int i = 0; i < dofs(); ++i) {
    const JerkProfile& p = profiles_[i];
    const KinematicState& c = current[i];
    const KinematicState& t = target[i];
    const KinematicState e = p.end();
    const auto miss = [](double value, double goal, double start) {
      return std::abs(value - goal) / std::max({1.0, std::abs(goal), std::abs(start)});
    };
    double end = std::max(miss(e.v, t.v, c.v), miss(e.a, t.a, c.a));
    if (!velocity_interface_) end = std::max(end, miss(e.p, t.p, c.p));
    const JerkLimits& l = limits_[i];
    const JerkExtrema x = p.extrema(brake_phases_[i]);
    double ratio = std::max(-x.a_min, x.a_max) / l.acceleration;
    if (!velocity_interface_) ratio = std::max(ratio, std::max(-x.v_min, x.v_max) / l.velocity);
    for (int k = 0; k < p.size(); ++k) ratio = std::max(ratio, std::abs(p.jerk(k)) / l.jerk);
    const double sync = std::abs(p.duration() - T);
    result_.end_error = std::max(result_.end_error, end);
    result_.limit_excess = std::max(result_.limit_excess, ratio - 1.0);
    result_.sync_error = std::max(result_.sync_error, sync);
    const bool ok = end <= OtgResult::kEndTolerance &&
                    ratio - 1.0 <= OtgResult::kLimitTolerance && sync <= sync_tolerance;
    if (failed < 0 && !ok) failed = i;  // NaN fails too
  }
  if (failed >= 0) {
    result_.status = OtgStatus::error_precision;
    result_.failed_dof = failed;
    return;
  }
  result_.status = T > 0.0 ? OtgStatus::working : OtgStatus::finished;
}

const JerkBlock& JerkLimitedGenerator::block(int i) const {
  const std::size_t k = static_cast<std::size_t>(i);
  if (!velocity_interface_ && !solved_.at(k)) solve_step1(i);  // one the sync did not need
  return blocks_.at(k);
}

OtgResult JerkLimitedGenerator::calculate_velocity(std::span<const KinematicState> current,
                                                   std::span<const KinematicState> target) {
  check_states(current, target, true);
  time_ = 0.0;
  result_ = OtgResult{};
  velocity_interface_ = true;
  const int n = dofs();
  for (int i = 0; i < n; ++i) {
    const JerkLimits& l = limits_[i];
    JerkProfile& p = profiles_[i];
    p.reset(current[i]);
    // an acceleration beyond its limit first ramps into it at full jerk
    if (std::abs(current[i].a) > l.acceleration)
      p.append(current[i].a > 0.0 ? -l.jerk : l.jerk,
               (std::abs(current[i].a) - l.acceleration) / l.jerk);
    brake_durations_[i] = p.duration();
    brake_phases_[i] = p.size();
    after_brake_[i] = p.end();
    if (!min_time_velocity_profile(after_brake_[i], target[i].v, target[i].a, l, blocks_[i])) {
      result_.status = OtgStatus::error_no_profile;
      result_.failed_dof = i;
      return result_;
    }
  }
  JerkSync sync;
  if (!synchronize(blocks_, brake_durations_, sync)) {
    result_.status = OtgStatus::error_synchronization;
    return result_;
  }
  result_.duration = sync.duration;
  result_.limiting_dof = sync.limiting_dof;
  for (int i = 0; i < n; ++i) {
    const double local = sync.duration - brake_durations_[i];
    if (const JerkPhases* extremal = blocks_[i].profile_of(local)) {
      extremal->append_to(profiles_[i]);
    } else if (!append_fixed_time_velocity_profile(after_brake_[i], target[i].v, target[i].a,
                                                   limits_[i], local, profiles_[i])) {
      result_.status = OtgStatus::error_synchronization;
      result_.failed_dof = i;
      return result_;
    }
  }
  check_result(current, target);
  return result_;
}

void JerkLimitedGenerator::at(double t, std::span<JerkSample> out) const noexcept {
  const std::size_t n = std::min(out.size(), profiles_.size());
  for (std::size_t i = 0; i < n; ++i) out[i] = profiles_[i].at(t);
}

void JerkLimitedGenerator::at(double t, TrajectorySample& sample) const {
  sample.resize(dofs());
  for (int i = 0; i < dofs(); ++i) {
    const JerkSample s = profiles_[static_cast<std::size_t>(i)].at(t);
    sample.position[i] = s.p;
    sample.velocity[i] = s.v;
    sample.acceleration[i] = s.a;
    sample.jerk[i] = t <= result_.duration ? s.j : 0.0;
  }
}

OtgStatus JerkLimitedGenerator::step(double dt, std::span<KinematicState> state) noexcept {
  if (result_.status != OtgStatus::working && result_.status != OtgStatus::finished)
    return result_.status;
  time_ += dt;
  const std::size_t n = std::min(state.size(), profiles_.size());
  for (std::size_t i = 0; i < n; ++i) {
    const JerkSample s = profiles_[i].at(time_);
    state[i] = {s.p, s.v, s.a};
  }
  return time_ >= result_.duration ? OtgStatus::finished : OtgStatus::working;
}

}  // namespace mjarm
