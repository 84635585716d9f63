#include "mjarm/env/time_step.hpp"

#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

std::span<const double> Observation::operator[](std::string_view name) const {
  if (spec_ == nullptr) throw Error("observation: empty (no reset yet)");
  return at(spec_->index(name));
}

std::span<const double> Observation::at(int i) const {
  if (spec_ == nullptr) throw Error("observation: empty (no reset yet)");
  if (i < 0 || i >= spec_->count())
    throw Error("observation: array index " + std::to_string(i) + " out of range [0, " +
                std::to_string(spec_->count()) + ")");
  return values_.subspan(static_cast<std::size_t>(spec_->offset(i)),
                         static_cast<std::size_t>(spec_->arrays()[i].size()));
}

}  // namespace mjarm
