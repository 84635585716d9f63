#pragma once
/// @file
/// The version of mjarm (the CMake project's, as `mjarm --version` prints it).

namespace mjarm {

/// "0.1.0": the project version this library was built as.
const char* version() noexcept;

}  // namespace mjarm
