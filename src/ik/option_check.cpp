#include "option_check.hpp"

#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm::detail {

OptionCheck OptionCheck::member(std::string_view name) const {
  return OptionCheck(prefix_ + std::string(name) + ".");
}

void OptionCheck::require(bool ok, std::string_view name, double value,
                          std::string_view expected) const {
  if (!ok) {
    throw Error(prefix_ + std::string(name) + " must be " + std::string(expected) + ", got " +
                number_text(value));
  }
}

void OptionCheck::positive(std::string_view name, double value) const {
  require(std::isfinite(value) && value > 0.0, name, value, "finite and > 0");
}

void OptionCheck::non_negative(std::string_view name, double value) const {
  require(std::isfinite(value) && value >= 0.0, name, value, "finite and >= 0");
}

void OptionCheck::at_least(std::string_view name, int value, int least) const {
  require(value >= least, name, value, ">= " + std::to_string(least));
}

}  // namespace mjarm::detail
