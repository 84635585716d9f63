#pragma once
/// @file
/// Step 2 of the jerk-limited generator: the synchronized duration of n DoF.

#include <span>

#include "mjarm/trajectory/otg/block.hpp"

namespace mjarm {

/// The duration every DoF will take and the DoF that sets it.
struct JerkSync {
  double duration = 0.0;  ///< synchronized duration [s]
  int limiting_dof = -1;  ///< the DoF whose minimum or blocked-interval end it is
};

/// The smallest duration T ≥ max over DoFs of (offsets[i] + blocks[i].t_min) that no DoF blocks:
/// T − offsets[i] is outside every blocked interval of DoF i. The candidates are each DoF's
/// offset + t_min and offset + upper end of each blocked interval (the feasible set of a DoF
/// is a union of closed intervals, so the answer is one of them). @p offsets are the durations
/// that precede each DoF's block (its brake pre-trajectory), same size as @p blocks.
/// @return false when the spans are empty or of different sizes. Never allocates, never throws.
bool synchronize(std::span<const JerkBlock> blocks, std::span<const double> offsets,
                 JerkSync& sync) noexcept;

/// As above over the DoFs i with @p active[i] ≠ 0 only (the others' blocks are not read);
/// @p active has the size of @p blocks. @return false also when no DoF is active.
bool synchronize(std::span<const JerkBlock> blocks, std::span<const double> offsets,
                 std::span<const char> active, JerkSync& sync) noexcept;

}  // namespace mjarm
