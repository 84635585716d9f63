#pragma once
/// @file
/// The generalized force the actuator of a chain joint can apply: its torque range (signed) and
/// limit (magnitude), from the model's ctrlrange, forcerange, gain and gear.

#include <limits>

#include "mjarm/model/chain.hpp"

namespace mjarm {

/// A closed interval of joint torque [N·m, or N for a slide]; ±infinity where unlimited.
struct TorqueRange {
  double lower =
      -std::numeric_limits<double>::infinity();  ///< most negative torque the actuator can apply
  double upper = std::numeric_limits<double>::infinity();  ///< most positive torque
};

/// The torque range of the actuator driving chain joint @p i: for a motor (fixed gain, no bias),
/// gear·gain·ctrlrange when ctrl-limited; for any actuator, gear·forcerange when force-limited;
/// the intersection when both (a negative gear flips the interval). (−inf, +inf) when the joint
/// has no actuator or none of these limits. Reads the model only.
TorqueRange joint_torque_range(const Chain& chain, int i);

/// The torque limit of chain joint @p i [N·m or N]: the ctrlrange (and forcerange) of its
/// actuator times the gain and gear, as a magnitude (the larger side of each range, the smaller
/// of the two ranges); +inf when it has no actuator or no limit.
double joint_torque_limit(const Chain& chain, int i);

}  // namespace mjarm
