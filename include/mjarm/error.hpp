#pragma once
/// @file
/// The one exception type mjarm throws at API boundaries.

#include <stdexcept>

namespace mjarm {

/// Bad input at an API boundary (unknown name, wrong size, non-finite value, unloadable model).
/// The message names the offending thing and what was expected. Hot loops never throw: they
/// return a status instead.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mjarm
