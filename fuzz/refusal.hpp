#pragma once
// What a fuzz target lets through: a clear refusal, `mjarm::Error`. Every other exception
// escapes (libFuzzer reports it as a crash, GoogleTest as a failure), as does any crash.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "mjarm/error.hpp"

namespace mjarm::fuzz {

/// The input as text (the readers take any bytes, NUL included).
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Runs @p read; returns 0 whether it accepted the input or refused it with `mjarm::Error`.
template <class Read>
int accept_or_refuse(Read&& read) {
  try {
    read();
  } catch (const mjarm::Error&) {
    // a clear refusal: what a reader must do with bad input
  }
  return 0;
}

}  // namespace mjarm::fuzz
