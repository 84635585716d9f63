// The profiles evaluate without heap allocation after construction (they run inside control
// ticks). The count is taken at malloc by the one counter of this executable,
// malloc_counter_test.cpp (the pattern of tests/ik/malloc_counter.hpp).

#include <gtest/gtest.h>

#include <cmath>

#include "ik/malloc_counter.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm {
namespace {

TEST(ProfileAllocation, EvaluationAllocatesNothing) {
  const Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(7, -1.0, 1.0);
  const Eigen::VectorXd q1 = Eigen::VectorXd::LinSpaced(7, 0.5, -0.2);
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(7);
  const SyncedTrapezoid trap(q0, q1, 1.0, 2.0);
  const QuinticTrajectory quintic({q0, Eigen::VectorXd::Constant(7, 0.3), z}, {q1, z, z}, 1.2);
  Vector6d V0 = Vector6d::Constant(0.2), A0 = Vector6d::Constant(-0.5);
  Pose X1;
  X1.p << 0.3, 0.2, 0.1;
  const Se3Interpolation se3(Pose::identity(), V0, A0, X1, 0.9);
  const SmoothRamp ramp(SmoothRamp::Kind::smootherstep, 0.4);
  Eigen::VectorXd q(7), qd(7), qdd(7), qddd(7);
  double sink = 0.0;

  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 50; ++k) {
    const double t = 0.03 * k;
    trap.at(t, q, qd, qdd);
    sink += q.sum() + trap.fraction(t);
    quintic.at(t, q, qd, qdd, qddd);
    sink += qddd.sum();
    sink += se3.at(t).V_WE.sum();
    sink += ramp.at(t).s + smoothstep(t).ds;
    sink += trap_profile(0.3).at(t).velocity;  // a new profile per move: no allocation either
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace mjarm
