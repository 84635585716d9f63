#include "mjarm/trajectory/otg/block.hpp"

#include <algorithm>
#include <cmath>

namespace mjarm {

JerkProfile JerkBlock::fastest() const noexcept {
  JerkProfile p;
  p.reset(start);
  if (duration_count > 0) profiles[0].append_to(p);
  return p;
}

void JerkBlock::record(double duration, const JerkPhases& phases) noexcept {
  for (int i = 0; i < duration_count; ++i)
    if (std::abs(durations[i] - duration) <= 1e-9 * std::max(1.0, duration)) return;
  int i = duration_count;
  if (duration_count < kMaxDurations) {
    ++duration_count;
  } else {
    if (duration >= durations[kMaxDurations - 1]) return;
    i = kMaxDurations - 1;
  }
  while (i > 0 && durations[i - 1] > duration) {
    durations[i] = durations[i - 1];
    profiles[i] = profiles[i - 1];
    --i;
  }
  durations[i] = duration;
  profiles[i] = phases;
}

const JerkPhases* JerkBlock::profile_of(double duration) const noexcept {
  for (int k = 0; k < duration_count; ++k)
    if (std::abs(durations[k] - duration) <= 1e-10 * std::max(1.0, duration)) return &profiles[k];
  return nullptr;
}

void JerkBlock::set_blocked_from_durations() noexcept {
  blocked_count = 0;
  for (int i = 1; i + 1 < duration_count && blocked_count < kMaxBlocked; i += 2)
    blocked[blocked_count++] = {durations[i], durations[i + 1]};
}

bool JerkBlock::is_blocked(double t) const noexcept {
  if (t < t_min) return true;
  for (int i = 0; i < blocked_count; ++i)
    if (t > blocked[i].lower && t < blocked[i].upper) return true;
  return false;
}

}  // namespace mjarm
