#include "base64.hpp"

#include <bit>

namespace mjarm::web_detail {

std::string base64(const void* data, std::size_t bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* in = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((bytes + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes; i += 3) {
    const unsigned v = (unsigned{in[i]} << 16) | (unsigned{in[i + 1]} << 8) | in[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < bytes) {
    const unsigned v = (unsigned{in[i]} << 16) | (i + 1 < bytes ? unsigned{in[i + 1]} << 8 : 0u);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// the page reads the arrays in the machine's order: typed arrays are little-endian on every
// platform a browser runs on, and so is every machine mjarm builds on
static_assert(std::endian::native == std::endian::little, "replay arrays are little-endian");

std::string base64_floats(std::span<const float> values) {
  return base64(values.data(), values.size_bytes());
}

std::string base64_uints(std::span<const unsigned> values) {
  return base64(values.data(), values.size_bytes());
}

}  // namespace mjarm::web_detail
