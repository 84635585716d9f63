#pragma once
// Helpers shared by the docking tests (one unity unit compiles them all together).

#include <numbers>
#include <string>

namespace mjarm::test {

/// One degree [rad].
inline constexpr double kDockingDeg = std::numbers::pi / 180.0;

/// True when @p text contains @p part.
inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace mjarm::test
