// The growth rule of the soak (soak/growth_check.hpp) on made-up samples: a leak, a step the
// allocator keeps, a transient peak, descriptors and threads after the warm-up.

#include "mjarm/soak/growth_check.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "mjarm/error.hpp"

namespace {

using mjarm::GrowthLimits;
using mjarm::SoakSample;

// @p n rounds of 30 s each, RSS from @p rss(k), 5 descriptors and 1 thread
template <class F>
std::vector<SoakSample> rounds_of(int n, F rss) {
  std::vector<SoakSample> samples;
  for (int k = 0; k < n; ++k) {
    SoakSample s;
    s.round = k + 1;
    s.elapsed_s = 30.0 * (k + 1);
    s.process.rss_kib = rss(k);
    s.process.heap_kib = 1000.0;
    s.process.fds = 5;
    s.process.threads = 1;
    samples.push_back(s);
  }
  return samples;
}

GrowthLimits growth_limits() {
  GrowthLimits limits;
  limits.warmup_rounds = 5;
  limits.warmup_fraction = 0.0;
  limits.max_heap_slope_kib_per_hour = 256.0;
  limits.heap_margin_kib = 256.0;
  limits.max_rss_slope_kib_per_hour = 2048.0;
  limits.rss_margin_kib = 8192.0;
  return limits;
}

TEST(GrowthCheck, LeastSquaresSlopeOfALineIsItsSlope) {
  const std::vector<double> x{0.0, 1.0, 2.0, 3.0}, y{1.0, 3.5, 6.0, 8.5};
  EXPECT_DOUBLE_EQ(mjarm::least_squares_slope(x, y), 2.5);
  EXPECT_EQ(mjarm::least_squares_slope(std::vector<double>{1.0}, std::vector<double>{2.0}), 0.0);
  EXPECT_EQ(mjarm::least_squares_slope(std::vector<double>{1.0, 1.0},
                                       std::vector<double>{2.0, 5.0}),
            0.0);
}

TEST(GrowthCheck, FlatMemoryDoesNotGrow) {
  const auto samples = rounds_of(100, [](int k) { return 50000.0 + (k % 3) * 100.0; });
  const auto r = mjarm::check_growth(samples, growth_limits());
  EXPECT_TRUE(r.judged);
  EXPECT_FALSE(r.rss.growth);
  EXPECT_FALSE(r.grew());
  EXPECT_EQ(r.warmup_rounds, 5);
  EXPECT_EQ(r.rss.first, 50000.0);
  EXPECT_EQ(r.rss.min, 50000.0);
  EXPECT_EQ(r.rss.max, 50200.0);
}

TEST(GrowthCheck, ASteadyLeakGrows) {
  // 100 KiB a round of 30 s: 12 MiB an hour, 9.5 MiB above the warm-up after 100 rounds
  const auto samples = rounds_of(100, [](int k) { return 50000.0 + 100.0 * k; });
  const auto r = mjarm::check_growth(samples, growth_limits());
  EXPECT_TRUE(r.rss.growth);
  EXPECT_NEAR(r.rss.slope, 100.0 * 120.0, 1e-6);  // KiB/h
  EXPECT_TRUE(r.grew());
}

TEST(GrowthCheck, GrowthNeedsBothTheSlopeAndTheRise) {
  // the same leak over 20 rounds: the slope is there, the rise (1.5 MiB) is within the margin
  const auto short_run = rounds_of(20, [](int k) { return 50000.0 + 100.0 * k; });
  EXPECT_FALSE(mjarm::check_growth(short_run, growth_limits()).rss.growth);
  // one step up at the end of the warm-up, kept: a rise, but no slope over the rest
  const auto step = rounds_of(100, [](int k) { return k < 4 ? 50000.0 : 70000.0; });
  const auto r = mjarm::check_growth(step, growth_limits());
  EXPECT_EQ(r.rss.slope, 0.0);
  EXPECT_EQ(r.rss.warmup_max, 70000.0);
  EXPECT_FALSE(r.rss.growth);
  // the last round's transient peak: a rise, but the slope of the rest is flat
  auto peak = rounds_of(100, [](int) { return 50000.0; });
  peak.back().process.rss_kib = 70000.0;
  EXPECT_FALSE(mjarm::check_growth(peak, growth_limits()).rss.growth);
}

TEST(GrowthCheck, AHeapLeakGrowsWhileTheResidentMemoryHidesIt) {
  // 3 KiB of heap a round of 30 s (360 KiB/h); the RSS flat (the allocator had the pages)
  auto samples = rounds_of(200, [](int) { return 50000.0; });
  for (int k = 0; k < 200; ++k)
    samples[static_cast<std::size_t>(k)].process.heap_kib = 1000.0 + 3.0 * k;
  auto r = mjarm::check_growth(samples, growth_limits());
  EXPECT_TRUE(r.heap.growth);
  EXPECT_NEAR(r.heap.slope, 3.0 * 120.0, 1e-6);
  EXPECT_FALSE(r.rss.growth);
  EXPECT_TRUE(r.grew());
  // one step up just after the warm-up (a cache filled once), then flat: a rise, no slope
  for (int k = 0; k < 200; ++k)
    samples[static_cast<std::size_t>(k)].process.heap_kib = k < 8 ? 1000.0 : 1300.0;
  r = mjarm::check_growth(samples, growth_limits());
  EXPECT_GT(r.heap.last - r.heap.warmup_max, 256.0);
  EXPECT_LT(r.heap.slope, 256.0);
  EXPECT_FALSE(r.heap.growth);
}

TEST(GrowthCheck, TheWarmUpIsAShareOfTheRoundsWhenThatIsLonger) {
  GrowthLimits limits = growth_limits();
  limits.warmup_fraction = 0.1;
  // memory that settles over the first 8 rounds of 100: no growth with a 10-round warm-up
  const auto samples = rounds_of(100, [](int k) { return 50000.0 + 4000.0 * std::min(k, 8); });
  const auto r = mjarm::check_growth(samples, limits);
  EXPECT_EQ(r.warmup_rounds, 10);
  EXPECT_FALSE(r.rss.growth);
  limits.warmup_fraction = 0.0;
  EXPECT_EQ(mjarm::check_growth(samples, limits).warmup_rounds, 5);
}

TEST(GrowthCheck, TooFewRoundsAreNotJudged) {
  const auto samples = rounds_of(7, [](int k) { return 50000.0 + 1e6 * k; });
  const auto r = mjarm::check_growth(samples, growth_limits());
  EXPECT_FALSE(r.judged);
  EXPECT_FALSE(r.rss.growth);
  EXPECT_EQ(r.rss.slope, 0.0);
  EXPECT_EQ(mjarm::check_growth({}, growth_limits()).samples, 0);
}

TEST(GrowthCheck, ADescriptorOrThreadAfterTheWarmUpGrows) {
  auto samples = rounds_of(10, [](int) { return 50000.0; });
  samples[2].process.fds = 7;  // during the warm-up: settles there
  EXPECT_FALSE(mjarm::check_growth(samples, growth_limits()).fd_growth);
  samples[8].process.fds = 8;
  auto r = mjarm::check_growth(samples, growth_limits());
  EXPECT_TRUE(r.fd_growth);
  EXPECT_EQ(r.fds_warmup_max, 7);
  EXPECT_EQ(r.fds_max, 8);
  EXPECT_EQ(r.fds_last, 5);
  EXPECT_FALSE(r.thread_growth);
  samples[9].process.threads = 2;
  r = mjarm::check_growth(samples, growth_limits());
  EXPECT_TRUE(r.thread_growth);
  EXPECT_EQ(r.threads_last, 2);
}

TEST(GrowthCheck, LimitsOutOfRangeAreRefused) {
  const auto samples = rounds_of(3, [](int) { return 1.0; });
  GrowthLimits limits = growth_limits();
  limits.warmup_rounds = 0;
  EXPECT_THROW(mjarm::check_growth(samples, limits), mjarm::Error);
  limits = growth_limits();
  limits.warmup_fraction = 1.0;
  EXPECT_THROW(mjarm::check_growth(samples, limits), mjarm::Error);
  limits = growth_limits();
  limits.rss_margin_kib = -1.0;
  EXPECT_THROW(mjarm::check_growth(samples, limits), mjarm::Error);
}

}  // namespace
