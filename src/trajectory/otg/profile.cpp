#include "mjarm/trajectory/otg/profile.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/trajectory/trajectory_sample.hpp"

namespace mjarm {

void JerkProfile::reset(const KinematicState& start) noexcept {
  size_ = 0;
  start_time_[0] = 0.0;
  state_[0] = start;
}

bool JerkProfile::append(double jerk, double duration) noexcept {
  if (size_ == kMaxPhases) return false;
  jerk_[size_] = jerk;
  start_time_[size_ + 1] = start_time_[size_] + duration;
  state_[size_ + 1] = integrate_jerk(state_[size_], jerk, duration);
  ++size_;
  return true;
}

bool JerkProfile::append_cruise(double duration) noexcept {
  if (size_ == kMaxPhases) return false;
  state_[size_].a = 0.0;
  return append(0.0, duration);
}

JerkSample JerkProfile::at(double t) const noexcept {
  JerkSample out;
  if (!(t > 0.0)) {
    out.p = state_[0].p;
    out.v = state_[0].v;
    out.a = state_[0].a;
    out.j = size_ > 0 ? jerk_[0] : 0.0;
    return out;
  }
  if (t >= duration()) {
    const KinematicState e = integrate_jerk(state_[size_], 0.0, t - duration());
    out.p = e.p;
    out.v = e.v;
    out.a = e.a;
    return out;
  }
  // the phase that holds t: the last whose start is ≤ t
  int i = 0;
  while (i + 1 < size_ && start_time_[i + 1] <= t) ++i;
  const KinematicState s = integrate_jerk(state_[i], jerk_[i], t - start_time_[i]);
  out.p = s.p;
  out.v = s.v;
  out.a = s.a;
  out.j = jerk_[i];
  return out;
}

JerkExtrema JerkProfile::extrema(int first_phase) const noexcept {
  JerkExtrema e;
  const int first = std::clamp(first_phase, 0, size_);
  e.v_min = e.v_max = state_[first].v;
  e.a_min = e.a_max = state_[first].a;
  for (int i = first; i < size_; ++i) {
    const KinematicState& s = state_[i];
    const KinematicState& n = state_[i + 1];
    e.v_min = std::min(e.v_min, n.v);
    e.v_max = std::max(e.v_max, n.v);
    e.a_min = std::min(e.a_min, n.a);
    e.a_max = std::max(e.a_max, n.a);
    // the velocity's turning point where the acceleration crosses zero inside the phase
    const double t = phase_duration(i);
    if (jerk_[i] != 0.0 && ((s.a < 0.0) != (n.a < 0.0))) {
      const double tz = std::clamp(-s.a / jerk_[i], 0.0, t);
      const double v = integrate_jerk(s, jerk_[i], tz).v;
      e.v_min = std::min(e.v_min, v);
      e.v_max = std::max(e.v_max, v);
    }
  }
  return e;
}

bool JerkProfile::within(const JerkLimits& limits, double relative) const noexcept {
  const JerkExtrema e = extrema();
  const double v = limits.velocity * (1.0 + relative);
  const double a = limits.acceleration * (1.0 + relative);
  const double j = limits.jerk * (1.0 + relative);
  for (int i = 0; i < size_; ++i)
    if (std::abs(jerk_[i]) > j) return false;
  return e.v_min >= -v && e.v_max <= v && e.a_min >= -a && e.a_max <= a;
}

}  // namespace mjarm

namespace mjarm {

double JerkPhases::total() const noexcept {
  double t = 0.0;
  for (const double d : duration) t += d;
  return t;
}

KinematicState JerkPhases::end(const KinematicState& start) const noexcept {
  KinematicState s = start;
  for (int i = 0; i < kSize; ++i) {
    if (!(duration[i] > 0.0)) continue;
    if (i == kCruise && jerk[i] == 0.0) s.a = 0.0;
    s = integrate_jerk(s, jerk[i], duration[i]);
  }
  return s;
}

bool JerkPhases::append_to(JerkProfile& profile) const noexcept {
  for (int i = 0; i < kSize; ++i) {
    if (!(duration[i] > 0.0)) continue;
    const bool ok = i == kCruise && jerk[i] == 0.0 ? profile.append_cruise(duration[i])
                                                   : profile.append(jerk[i], duration[i]);
    if (!ok) return false;
  }
  return true;
}

void JerkProfile::at(double t, TrajectorySample& sample) const {
  sample.resize(1);
  const JerkSample s = at(t);
  sample.position[0] = s.p;
  sample.velocity[0] = s.v;
  sample.acceleration[0] = s.a;
  sample.jerk[0] = s.j;
}

}  // namespace mjarm
