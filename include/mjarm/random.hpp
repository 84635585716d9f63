#pragma once
/// @file
/// Random numbers: one seeded generator type and the few distributions mjarm draws from,
/// written here so that a seed gives the same numbers on every platform. The generator's bits
/// are fixed by the C++ standard; the `std::*_distribution` classes are not (each standard
/// library turns the bits into numbers its own way), so mjarm uses none of them.

#include <cstdint>
#include <random>

namespace mjarm {

/// The generator of every seeded draw in mjarm: the 64-bit Mersenne Twister, whose sequence the
/// C++ standard fixes (its 10000th output from the default seed 5489 is 9981545732273789042), so
/// that a seed gives the same bits everywhere. Seed one per run (or per episode, per case) and
/// draw with the functions below; never share one between threads.
using Random = std::mt19937_64;

/// SplitMix64's finalizer: a well-mixed 64-bit function of @p x, for seeds derived from one
/// seed (an episode's, an environment's in a vector, …).
std::uint64_t splitmix64(std::uint64_t x) noexcept;

/// A number in [0, 1) from the top 53 bits of @p bits: k·2⁻⁵³ with k = bits >> 11, so every
/// multiple of 2⁻⁵³ in [0, 1) is equally likely (0 can come, 1 cannot).
constexpr double unit_draw(std::uint64_t bits) noexcept {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

/// Uniform in [0, 1): `unit_draw` of one draw of @p rng.
inline double uniform(Random& rng) noexcept { return unit_draw(rng()); }

/// Uniform in [@p lo, @p hi): lo + (hi − lo)·u with u = uniform(rng), one draw (rounding can give
/// hi itself for the largest u; lo > hi draws in (hi, lo]).
inline double uniform(Random& rng, double lo, double hi) noexcept {
  return lo + (hi - lo) * uniform(rng);
}

/// Standard normal (mean 0, standard deviation 1) by Marsaglia's polar method: x, y uniform in
/// [−1, 1) until 0 < s = x² + y² < 1, then x·√(−2 ln s / s). Two draws per try, 4/π tries on
/// average; the pair's second normal (y·√(…)) is not kept, so a call depends on the generator's
/// state alone. Bit for bit the same on every platform whose std::log rounds alike (IEEE 754
/// requires correct rounding of sqrt, not of log; glibc's log is within one ulp).
double normal(Random& rng) noexcept;

/// Normal with @p mean and standard deviation @p sigma: mean + sigma·normal(rng).
inline double normal(Random& rng, double mean, double sigma) noexcept {
  return mean + sigma * normal(rng);
}

/// An integer uniform in [0, @p n) without modulo bias: a draw below 2⁶⁴ mod n is drawn again
/// (for any n fewer than half of the draws), the others are taken mod n. n = 0 gives 0.
std::uint64_t uniform_index(Random& rng, std::uint64_t n) noexcept;

/// An integer uniform in [@p lo, @p hi], both ends included (`uniform_index` of the range's
/// size); lo > hi gives lo.
std::int64_t uniform_integer(Random& rng, std::int64_t lo, std::int64_t hi) noexcept;

}  // namespace mjarm
