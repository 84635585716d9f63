#include "mjarm/fields.hpp"

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

std::string Range::text(bool integer) const {
  const bool low = min > -inf;
  const bool high = max < inf;
  // "finite" is said only of real numbers whose interval is open towards infinity
  const bool say_finite = !integer && !allow_infinity && (!low || !high);
  if (low && high) {
    return std::string("in ") + (min_open ? "(" : "[") + number_text(min) + ", " +
           number_text(max) + (max_open ? ")" : "]");
  }
  if (low) {
    if (min == 0.0 && min_open) {
      if (integer) return "≥ 1";
      return allow_infinity ? "positive (+inf allowed)" : "positive and finite";
    }
    const std::string bound = std::string(min_open ? "> " : "≥ ") + number_text(min);
    if (integer) return bound;
    return say_finite ? "finite and " + bound : bound + " (+inf allowed)";
  }
  if (high) {
    const std::string bound = std::string(max_open ? "< " : "≤ ") + number_text(max);
    if (integer) return bound;
    return say_finite ? "finite and " + bound : bound + " (-inf allowed)";
  }
  if (integer) return "a whole number";
  return allow_infinity ? "a number" : "finite";
}

namespace detail {

std::string owner_prefix(std::string_view owner) {
  return owner.empty() ? std::string() : std::string(owner) + ": ";
}

void throw_unknown_enum_name(std::string_view kind, std::string_view word,
                             const std::vector<std::string>& known, std::string_view where) {
  throw Error(unknown_name_message(kind, word, known, where));
}

void throw_out_of_range(std::string_view owner, std::string_view path, const Range& range,
                        std::string_view unit, double value, bool integer) {
  std::string message = owner_prefix(owner) + std::string(path) + " must be " + range.text(integer);
  if (!unit.empty()) message += " [" + std::string(unit) + "]";
  message += ", got " + (integer ? std::to_string(static_cast<long long>(value)) : number_text(value));
  throw Error(message);
}

void throw_unnamed_enum(std::string_view owner, std::string_view path, long value) {
  throw Error(owner_prefix(owner) + std::string(path) + " holds " + std::to_string(value) +
              ", which names no value");
}

}  // namespace detail
}  // namespace mjarm
