#include "mjarm/trajectory/otg/validation/grid_reference.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

// Rest to rest over 1 with v, a, j = 1, 2, 10 takes 1/1 + 1/2 + 2/10 = 1.7 s exactly when
// all limits are reached (the classic formula, independent of the solvers).
TEST(JerkLimitedReference, AgreesWithTheClassicRestToRestDuration) {
  const JerkLimits l{1.0, 2.0, 10.0};
  const KinematicState start{0.0, 0.0, 0.0}, target{1.0, 0.0, 0.0};
  EXPECT_FALSE(grid_motion_exists(start, target, l, 1.65, 120));
  EXPECT_FALSE(grid_motion_exists(start, target, l, 1.0, 120));
  EXPECT_TRUE(grid_motion_exists(start, target, l, 1.8, 120));
  EXPECT_TRUE(grid_motion_exists(start, target, l, 3.0, 120));
}

TEST(JerkLimitedReference, RejectsBadGrids) {
  const JerkLimits l{1.0, 2.0, 10.0};
  EXPECT_THROW(grid_motion_exists({}, {}, l, 1.0, 0), Error);
  EXPECT_THROW(grid_motion_exists({}, {}, l, -1.0, 10), Error);
}

}  // namespace
}  // namespace mjarm
