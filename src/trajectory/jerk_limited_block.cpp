#include "mjarm/trajectory/jerk_limited_block.hpp"

namespace mjarm {

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
