#include "mjarm/number_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace mjarm {

std::string number_text(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[32];  // the shortest form of a double needs at most 24 characters
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

std::string number_text(double value, int significant_digits) {
  if (!std::isfinite(value)) return number_text(value);
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", significant_digits, value);
  return text;
}

std::optional<double> number_from_text(std::string_view text) {
  // a sign that only says "positive", as people write it; std::from_chars takes '-' only
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto parsed = std::from_chars(text.data(), end, value);
  if (text.empty() || parsed.ec != std::errc() || parsed.ptr != end) return std::nullopt;
  return value;
}

}  // namespace mjarm
