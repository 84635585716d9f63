#include "mjarm/trajectory/otg/sync.hpp"

#include <algorithm>
#include <cmath>

namespace mjarm {

namespace {

/// True when no DoF (of those @p active, all when empty) blocks the total duration @p t.
bool free_for_all(std::span<const JerkBlock> blocks, std::span<const double> offsets,
                  std::span<const char> active, double t) noexcept {
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!active.empty() && !active[i]) continue;
    const JerkBlock& b = blocks[i];
    const double local = t - offsets[i];
    // t_min itself is feasible (round-off may put local a hair below it)
    if (local < b.t_min - 1e-12 * std::max(1.0, b.t_min)) return false;
    // an interval's ends are feasible; offset + end − offset may land a hair inside
    for (int k = 0; k < b.blocked_count; ++k) {
      const double eps = 1e-12 * std::max(1.0, b.blocked[k].upper);
      if (local > b.blocked[k].lower + eps && local < b.blocked[k].upper - eps) return false;
    }
  }
  return true;
}

}  // namespace

bool synchronize(std::span<const JerkBlock> blocks, std::span<const double> offsets,
                 JerkSync& sync) noexcept {
  return synchronize(blocks, offsets, {}, sync);
}

bool synchronize(std::span<const JerkBlock> blocks, std::span<const double> offsets,
                 std::span<const char> active, JerkSync& sync) noexcept {
  if (blocks.empty() || blocks.size() != offsets.size()) return false;
  if (!active.empty() && active.size() != blocks.size()) return false;
  double lower = 0.0;
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (active.empty() || active[i]) lower = std::max(lower, offsets[i] + blocks[i].t_min);
  sync.duration = HUGE_VAL;
  sync.limiting_dof = -1;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!active.empty() && !active[i]) continue;
    const JerkBlock& b = blocks[i];
    for (int k = -1; k < b.blocked_count; ++k) {
      const double t = offsets[i] + (k < 0 ? b.t_min : b.blocked[k].upper);
      if (t < lower || t >= sync.duration) continue;
      if (!free_for_all(blocks, offsets, active, t)) continue;
      sync.duration = t;
      sync.limiting_dof = static_cast<int>(i);
    }
  }
  return sync.limiting_dof >= 0;
}

}  // namespace mjarm
