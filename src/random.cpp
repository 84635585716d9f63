#include "mjarm/random.hpp"

#include <cmath>

namespace mjarm {

std::uint64_t splitmix64(std::uint64_t x) noexcept {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double normal(Random& rng) noexcept {
  for (;;) {
    const double x = uniform(rng, -1.0, 1.0);
    const double y = uniform(rng, -1.0, 1.0);
    const double s = x * x + y * y;
    if (s > 0.0 && s < 1.0) return x * std::sqrt(-2.0 * std::log(s) / s);
  }
}

std::uint64_t uniform_index(Random& rng, std::uint64_t n) noexcept {
  if (n == 0) return 0;
  // 2⁶⁴ mod n draws are the surplus of the last, incomplete round of n: drop the lowest ones
  const std::uint64_t surplus = (std::uint64_t{0} - n) % n;
  for (;;) {
    const std::uint64_t bits = rng();
    if (bits >= surplus) return bits % n;
  }
}

std::int64_t uniform_integer(Random& rng, std::int64_t lo, std::int64_t hi) noexcept {
  if (lo >= hi) return lo;
  // the size of [lo, hi] in unsigned arithmetic (wraps to 0 for the whole 64-bit range)
  const std::uint64_t size = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo) + 1;
  const std::uint64_t offset = size == 0 ? rng() : uniform_index(rng, size);
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(lo) + offset);
}

}  // namespace mjarm
