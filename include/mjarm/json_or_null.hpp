#pragma once
/// @file
/// JSON for a value that may be missing: a number that is not finite (a metric that did not
/// happen, an undefined ratio) and an empty text (no error) are written as null.

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

namespace mjarm {

/// @p x, or null when it is NaN or infinite.
inline nlohmann::ordered_json number_or_null(double x) {
  return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
}

/// @p text, or null when it is empty.
inline nlohmann::ordered_json text_or_null(const std::string& text) {
  return text.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(text);
}

}  // namespace mjarm
