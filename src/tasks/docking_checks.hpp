#pragma once
// Checks of the docking options (scene, motion, criteria, controller, gate): one message shape,
// "<who>: <what> must be positive and finite, got <value>". Internal to the tasks room.

#include <cmath>
#include <string>
#include <string_view>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm::docking_detail {

/// @throws Error "<who>: <what> must be positive and finite, got <value>".
inline void require_positive(double value, std::string_view who, std::string_view what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(std::string(who) + ": " + std::string(what) + " must be positive and finite, got " +
                number_text(value));
}

/// @throws Error "<who>: <what> must be ≥ 0 and finite, got <value>".
inline void require_non_negative(double value, std::string_view who, std::string_view what) {
  if (!(value >= 0.0) || !std::isfinite(value))
    throw Error(std::string(who) + ": " + std::string(what) + " must be ≥ 0 and finite, got " +
                number_text(value));
}

}  // namespace mjarm::docking_detail
