// random.hpp: the first numbers of a fixed seed pinned and recomputed by hand from the raw
// engine output, the engine's own sequence as the C++ standard fixes it, ranges, moments and the
// absence of modulo bias on a few hundred thousand draws, and seeds that repeat.

#include "mjarm/random.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace {

using mjarm::Random;

constexpr int kDraws = 400000;

// [0, 1) by hand: the top 53 bits of one raw draw, scaled by 2⁻⁵³
double by_hand_unit(std::mt19937_64& raw) {
  return std::ldexp(static_cast<double>(raw() >> 11), -53);
}

TEST(Random, TheEngineIsTheStandardsMersenneTwister) {
  // [rand.predef]: the 10000th output of a default-constructed mt19937_64
  Random rng;
  rng.discard(9999);
  EXPECT_EQ(rng(), 9981545732273789042ull);
}

TEST(Random, UniformFirstNumbersArePinnedAndMatchTheRawBits) {
  const std::array<double, 3> pinned{0x1.39b1c9e957cb2p-1, 0x1.96e50634f5cdbp-1,
                                     0x1.10086ce6c6f18p-2};
  Random rng(2024);
  std::mt19937_64 raw(2024);
  for (double expected : pinned) {
    const double by_hand = by_hand_unit(raw);
    EXPECT_EQ(by_hand, expected);
    EXPECT_EQ(mjarm::uniform(rng), expected);
  }
  // [lo, hi): lo + (hi − lo)·u of the same draw
  Random again(2024);
  EXPECT_EQ(mjarm::uniform(again, -2.0, 6.0), -2.0 + 8.0 * pinned[0]);
}

TEST(Random, UnitDrawKeepsTheTop53Bits) {
  EXPECT_EQ(mjarm::unit_draw(0), 0.0);
  EXPECT_EQ(mjarm::unit_draw(~std::uint64_t{0}), 1.0 - 0x1.0p-53);
  EXPECT_EQ(mjarm::unit_draw(std::uint64_t{1} << 63), 0.5);
  EXPECT_EQ(mjarm::unit_draw((std::uint64_t{1} << 11) - 1), 0.0);  // the low 11 bits drop
  EXPECT_EQ(mjarm::unit_draw(std::uint64_t{1} << 11), 0x1.0p-53);
}

TEST(Random, NormalFirstNumbersArePinnedAndMatchThePolarMethodByHand) {
  const std::array<double, 3> pinned{0x1.f044db830627cp-2, -0x1.377743b6de7adp+0,
                                     0x1.64ef4ccebcf44p-1};
  Random rng(2024);
  std::mt19937_64 raw(2024);
  for (double expected : pinned) {
    // Marsaglia's polar method on the raw draws: a point of the square [−1, 1)², kept inside
    // the unit disc (the origin excluded), then x·√(−2 ln s / s)
    double by_hand = 0.0;
    for (;;) {
      const double x = 2.0 * by_hand_unit(raw) - 1.0;
      const double y = 2.0 * by_hand_unit(raw) - 1.0;
      const double s = x * x + y * y;
      if (s > 0.0 && s < 1.0) {
        by_hand = x * std::sqrt(-2.0 * std::log(s) / s);
        break;
      }
    }
    EXPECT_EQ(by_hand, expected);
    EXPECT_EQ(mjarm::normal(rng), expected);
  }
  Random again(2024);
  EXPECT_EQ(mjarm::normal(again, 1.5, 0.25), 1.5 + 0.25 * pinned[0]);
}

TEST(Random, IntegerFirstNumbersArePinnedAndMatchTheRawBits) {
  // 2⁶⁴ mod 1000 = 616: a raw draw below it is drawn again (none of these five is)
  const std::array<std::uint64_t, 5> pinned{974, 969, 181, 714, 12};
  Random rng(2024);
  std::mt19937_64 raw(2024);
  for (std::uint64_t expected : pinned) {
    std::uint64_t bits = raw();
    while (bits < 616) bits = raw();
    EXPECT_EQ(bits % 1000, expected);
    EXPECT_EQ(mjarm::uniform_index(rng, 1000), expected);
  }
  // [lo, hi]: lo + an index below hi − lo + 1
  Random a(2024), b(2024);
  for (int k = 0; k < 5; ++k)
    EXPECT_EQ(mjarm::uniform_integer(a, -3, 3),
              -3 + static_cast<std::int64_t>(mjarm::uniform_index(b, 7)));
}

TEST(Random, IndexRedrawsTheSurplusOfALargeRange) {
  // n = 2⁶³ + 1: 2⁶⁴ mod n = 2⁶³ − 1, so about half the raw draws are drawn again; by hand
  const std::uint64_t n = (std::uint64_t{1} << 63) + 1;
  const std::uint64_t surplus = (std::uint64_t{1} << 63) - 1;
  Random rng(5);
  std::mt19937_64 raw(5);
  int redrawn = 0;
  for (int k = 0; k < 1000; ++k) {
    std::uint64_t bits = raw();
    while (bits < surplus) {
      bits = raw();
      ++redrawn;
    }
    ASSERT_EQ(mjarm::uniform_index(rng, n), bits % n) << k;
  }
  EXPECT_GT(redrawn, 300);  // the branch was taken
  EXPECT_EQ(rng(), raw());  // both consumed the same draws
}

TEST(Random, EdgeCasesOfTheIntegerDraws) {
  Random rng(3);
  for (int k = 0; k < 100; ++k) {
    EXPECT_EQ(mjarm::uniform_index(rng, 1), 0u);
    EXPECT_EQ(mjarm::uniform_index(rng, 0), 0u);
    EXPECT_EQ(mjarm::uniform_integer(rng, 5, 5), 5);
    EXPECT_EQ(mjarm::uniform_integer(rng, 5, -5), 5);  // lo > hi: lo
  }
  // the whole 64-bit range: one raw draw, as two's complement
  const std::int64_t lo = std::numeric_limits<std::int64_t>::min();
  const std::int64_t hi = std::numeric_limits<std::int64_t>::max();
  Random a(9);
  std::mt19937_64 raw(9);
  for (int k = 0; k < 10; ++k)
    EXPECT_EQ(mjarm::uniform_integer(a, lo, hi),
              static_cast<std::int64_t>(static_cast<std::uint64_t>(lo) + raw()));
}

TEST(Random, UniformStaysInItsRangeWithTheMomentsOfAUniform) {
  Random rng(11);
  double sum = 0.0, sum2 = 0.0, low = 1.0, high = 0.0;
  for (int k = 0; k < kDraws; ++k) {
    const double u = mjarm::uniform(rng);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    low = std::min(low, u);
    high = std::max(high, u);
    sum += u;
    sum2 += u * u;
  }
  const double mean = sum / kDraws, variance = sum2 / kDraws - mean * mean;
  // five standard errors: sd(mean) = √(1/12/N) ≈ 4.6e-4, sd(variance) ≈ √((1/80 − 1/144)/N)
  EXPECT_NEAR(mean, 0.5, 5 * std::sqrt(1.0 / 12.0 / kDraws));
  EXPECT_NEAR(variance, 1.0 / 12.0, 5 * std::sqrt((1.0 / 80.0 - 1.0 / 144.0) / kDraws));
  EXPECT_LT(low, 1e-4);
  EXPECT_GT(high, 1.0 - 1e-4);
  for (int k = 0; k < kDraws / 10; ++k) {
    const double x = mjarm::uniform(rng, -2.5, 4.0);
    ASSERT_GE(x, -2.5);
    ASSERT_LT(x, 4.0);
  }
}

TEST(Random, NormalHasTheMomentsOfAStandardNormal) {
  Random rng(12);
  double m1 = 0.0, m2 = 0.0, m3 = 0.0, m4 = 0.0;
  int within_one = 0;
  for (int k = 0; k < kDraws; ++k) {
    const double z = mjarm::normal(rng);
    ASSERT_TRUE(std::isfinite(z));
    m1 += z;
    m2 += z * z;
    m3 += z * z * z;
    m4 += z * z * z * z;
    within_one += std::abs(z) < 1.0;
  }
  const double n = kDraws;
  // five standard errors of each sample moment of N(0, 1): √(1/N), √(2/N), √(15/N), √(96/N)
  EXPECT_NEAR(m1 / n, 0.0, 5 * std::sqrt(1.0 / n));
  EXPECT_NEAR(m2 / n, 1.0, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(m3 / n, 0.0, 5 * std::sqrt(15.0 / n));
  EXPECT_NEAR(m4 / n, 3.0, 5 * std::sqrt(96.0 / n));
  const double p = std::erf(1.0 / std::sqrt(2.0));  // P(|z| < 1) = 0.6827
  EXPECT_NEAR(within_one / n, p, 5 * std::sqrt(p * (1 - p) / n));
}

TEST(Random, IntegersAreUniformWithoutModuloBias) {
  // [−3, 3]: seven counts against N/7 (χ² with 6 degrees of freedom; 30 is beyond its 0.9999
  // quantile, 27.9), both ends reached
  Random rng(13);
  std::array<int, 7> counts{};
  for (int k = 0; k < kDraws; ++k) {
    const std::int64_t v = mjarm::uniform_integer(rng, -3, 3);
    ASSERT_GE(v, -3);
    ASSERT_LE(v, 3);
    ++counts[static_cast<std::size_t>(v + 3)];
  }
  double chi2 = 0.0;
  for (int c : counts) chi2 += (c - kDraws / 7.0) * (c - kDraws / 7.0) / (kDraws / 7.0);
  EXPECT_LT(chi2, 30.0);
  // n = 3·2⁶²: a plain raw % n would give [0, 2⁶²) half the time instead of a third
  const std::uint64_t n = 3 * (std::uint64_t{1} << 62);
  int low = 0;
  for (int k = 0; k < kDraws; ++k) {
    const std::uint64_t v = mjarm::uniform_index(rng, n);
    ASSERT_LT(v, n);
    low += v < (std::uint64_t{1} << 62);
  }
  EXPECT_NEAR(low / static_cast<double>(kDraws), 1.0 / 3.0, 5 * std::sqrt(2.0 / 9.0 / kDraws));
}

TEST(Random, TheSameSeedGivesTheSameSequence) {
  const auto sequence = [](std::uint64_t seed) {
    Random rng(seed);
    std::vector<double> out;
    for (int k = 0; k < 1000; ++k) {
      out.push_back(mjarm::uniform(rng));
      out.push_back(mjarm::normal(rng));
      out.push_back(static_cast<double>(mjarm::uniform_integer(rng, -50, 50)));
    }
    return out;
  };
  EXPECT_EQ(sequence(77), sequence(77));
  EXPECT_NE(sequence(77), sequence(78));
  // reseeding starts the sequence again
  Random rng(77);
  const double first = mjarm::uniform(rng);
  rng.seed(77);
  EXPECT_EQ(mjarm::uniform(rng), first);
}

TEST(Random, SplitMix64IsTheReferenceFinalizer) {
  // SplitMix64's first output from state 0 (its published test value)
  EXPECT_EQ(mjarm::splitmix64(0), 0xe220a8397b1dcdafull);
  EXPECT_NE(mjarm::splitmix64(1), mjarm::splitmix64(2));
}

}  // namespace
