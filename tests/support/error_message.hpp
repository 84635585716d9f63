#pragma once
/// @file
/// The message a call throws, for tests that check what an error says.

#include <string>

#include "mjarm/error.hpp"

namespace mjarm::test {

/// The message of the mjarm::Error @p f throws, or "(no error)".
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace mjarm::test
