#pragma once
/// @file
/// Base64 (RFC 4648, with padding) of raw bytes: the replay's arrays inside its JSON block.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace mjarm::web_detail {

std::string base64(const void* data, std::size_t bytes);

/// Base64 of @p values as little-endian 32-bit floats (the page's Float32Array).
std::string base64_floats(std::span<const float> values);
/// Base64 of @p values as 32-bit unsigned integers (the page's Uint32Array).
std::string base64_uints(std::span<const unsigned> values);

}  // namespace mjarm::web_detail
