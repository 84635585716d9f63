#include "mjarm/trajectory/otg/sync.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace mjarm {
namespace {

JerkBlock jerk_block(double t_min, std::vector<double> more = {}) {
  JerkBlock b;
  b.t_min = t_min;
  b.durations[0] = t_min;
  b.duration_count = 1;
  for (const double d : more) b.durations[b.duration_count++] = d;
  b.set_blocked_from_durations();
  return b;
}

TEST(JerkLimitedBlock, ThreeExtremalDurationsBlockTheMiddleGap) {
  const JerkBlock b = jerk_block(1.0, {1.5, 2.5});
  ASSERT_EQ(b.blocked_count, 1);
  EXPECT_EQ(b.blocked[0].lower, 1.5);
  EXPECT_EQ(b.blocked[0].upper, 2.5);
  EXPECT_TRUE(b.is_blocked(0.9));
  EXPECT_FALSE(b.is_blocked(1.2));
  EXPECT_TRUE(b.is_blocked(2.0));
  EXPECT_FALSE(b.is_blocked(2.5));
  EXPECT_FALSE(b.is_blocked(7.0));
  EXPECT_EQ(jerk_block(1.0, {1.5}).blocked_count, 0);  // two: nothing blocked
}

TEST(JerkLimitedSync, TheSlowestDoFSetsTheDurationUnlessAnotherBlocksIt) {
  const double none[] = {0.0, 0.0};
  JerkSync sync;
  {
    const JerkBlock blocks[] = {jerk_block(1.0), jerk_block(2.0)};
    ASSERT_TRUE(synchronize(blocks, none, sync));
    EXPECT_EQ(sync.duration, 2.0);
    EXPECT_EQ(sync.limiting_dof, 1);
  }
  {
    // DoF 0 cannot take durations in (1.5, 2.5): the answer is 2.5, set by DoF 0's interval
    const JerkBlock blocks[] = {jerk_block(1.0, {1.5, 2.5}), jerk_block(2.0)};
    ASSERT_TRUE(synchronize(blocks, none, sync));
    EXPECT_EQ(sync.duration, 2.5);
    EXPECT_EQ(sync.limiting_dof, 0);
  }
  {
    // offsets (brake pre-trajectories) shift a DoF's durations
    const JerkBlock blocks[] = {jerk_block(1.0, {1.5, 2.5}), jerk_block(2.0)};
    const double offsets[] = {0.6, 0.0};
    ASSERT_TRUE(synchronize(blocks, offsets, sync));
    EXPECT_EQ(sync.duration, 2.0);  // 2.0 − 0.6 = 1.4 is free for DoF 0
  }
  {
    // overlapping blocked intervals of two DoFs push past both
    const JerkBlock blocks[] = {jerk_block(1.0, {1.5, 2.5}), jerk_block(2.0, {2.1, 3.0})};
    ASSERT_TRUE(synchronize(blocks, none, sync));
    EXPECT_EQ(sync.duration, 3.0);
    EXPECT_EQ(sync.limiting_dof, 1);
  }
  {
    // an interval's upper end reached through an offset that does not round-trip exactly
    const double offsets[] = {0.0, 0.7};  // (7.77… + 0.7) − 0.7 < 7.77… in doubles
    const JerkBlock blocks[] = {
        jerk_block(3.0), jerk_block(1.2896800400012693, {1.6077583663995674, 7.7748450053870037})};
    ASSERT_TRUE(synchronize(blocks, offsets, sync));
    EXPECT_NEAR(sync.duration, 7.7748450053870037 + 0.7, 1e-15);
    EXPECT_EQ(sync.limiting_dof, 1);
  }
  const JerkBlock one[] = {jerk_block(1.0)};
  EXPECT_FALSE(synchronize(one, none, sync));  // sizes differ
}

// Only the active DoFs count: an inactive DoF's minimum and blocked intervals are ignored.
TEST(JerkLimitedSync, InactiveDoFsAreIgnored) {
  const double none[] = {0.0, 0.0, 0.0};
  const JerkBlock blocks[] = {jerk_block(1.0, {1.5, 2.5}), jerk_block(2.0), jerk_block(5.0)};
  JerkSync sync;
  const char first_two[] = {1, 1, 0};
  ASSERT_TRUE(synchronize(blocks, none, first_two, sync));
  EXPECT_EQ(sync.duration, 2.5);
  EXPECT_EQ(sync.limiting_dof, 0);
  const char second[] = {0, 1, 0};
  ASSERT_TRUE(synchronize(blocks, none, second, sync));
  EXPECT_EQ(sync.duration, 2.0);
  const char nothing[] = {0, 0, 0};
  EXPECT_FALSE(synchronize(blocks, none, nothing, sync));
  const char wrong_size[] = {1, 1};
  EXPECT_FALSE(synchronize(blocks, none, wrong_size, sync));
}

}  // namespace
}  // namespace mjarm
