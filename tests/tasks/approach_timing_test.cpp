#include "mjarm/tasks/approach_timing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/trajectory/smoothstep.hpp"

namespace mjarm {
namespace {

/// Largest |τ − τ_rest| / (fraction·limit − |τ_rest|) along the move, on a grid finer than the
/// function's (an independent check with mj_inverse).
double worst_ratio(const Chain& chain, const std::vector<double>& qpos, const Eigen::VectorXd& q1,
                   double T, double fraction) {
  const mjModel& m = chain.robot().model();
  DataPtr d = chain.robot().make_data();
  const Eigen::VectorXd q0 = chain.gather(qpos.data());
  const SmoothRamp profile(SmoothRamp::Kind::smootherstep, T);
  double worst = 0.0;
  for (int k = 0; k <= 1000; ++k) {
    const auto s = profile.at(T * k / 1000.0);
    std::copy(qpos.begin(), qpos.end(), d->qpos);
    chain.scatter(q0 + s.s * (q1 - q0), d->qpos);
    mju_zero(d->qvel, m.nv);
    mju_zero(d->qacc, m.nv);
    mj_inverse(&m, d.get());
    std::vector<double> rest(d->qfrc_inverse, d->qfrc_inverse + m.nv);
    for (int i = 0; i < chain.size(); ++i) {
      d->qvel[chain.dof_address(i)] = s.ds * (q1 - q0)[i];
      d->qacc[chain.dof_address(i)] = s.dds * (q1 - q0)[i];
    }
    mj_inverse(&m, d.get());
    for (int i = 0; i < chain.size(); ++i) {
      const int dof = chain.dof_address(i);
      const double room = fraction * joint_torque_limit(chain, i) - std::abs(rest[dof]);
      worst = std::max(worst, std::abs(d->qfrc_inverse[dof] - rest[dof]) / room);
    }
  }
  return worst;
}

TEST(ApproachTiming, TorqueLimitsComeFromTheMotors) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  EXPECT_EQ(joint_torque_limit(chain, 0), 87.0);
  EXPECT_EQ(joint_torque_limit(chain, 6), 12.0);
  // position servos: the forcerange
  const Robot servo = Robot::bundled("planar2");
  EXPECT_EQ(joint_torque_limit(Chain(servo, "tip"), 1), 10.0);
}

TEST(ApproachTiming, AStretchedMoveStaysWithinTheTorqueBudget) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  const std::vector<double> home = robot.keyframe_qpos("home");
  Eigen::VectorXd q1 = chain.gather(home.data());
  q1[1] += 0.5;  // a big shoulder move
  q1[3] += 0.4;
  const double fraction = 0.7;
  const double T0 = 0.15;
  ASSERT_GT(worst_ratio(chain, home, q1, T0, fraction), 1.5);  // too fast as asked
  const double T = torque_feasible_duration(chain, home, q1, T0, fraction);
  EXPECT_GT(T, T0);
  const double ratio = worst_ratio(chain, home, q1, T, fraction);
  EXPECT_LE(ratio, 1.02);
  EXPECT_GE(ratio, 0.9);  // and not stretched more than needed
}

TEST(ApproachTiming, AFeasibleMoveKeepsItsDuration) {
  const Robot robot = Robot::bundled("planar2_torque");
  const Chain chain(robot, "tip");
  const std::vector<double> home = robot.keyframe_qpos("home");
  Eigen::VectorXd q1 = chain.gather(home.data());
  q1[0] += 0.05;
  EXPECT_EQ(torque_feasible_duration(chain, home, q1, 0.5, 0.7), 0.5);
}

TEST(ApproachTiming, RejectsBadInput) {
  const Robot robot = Robot::bundled("planar2_torque");
  const Chain chain(robot, "tip");
  const std::vector<double> home = robot.keyframe_qpos("home");
  const Eigen::VectorXd q1 = chain.gather(home.data());
  EXPECT_THROW(torque_feasible_duration(chain, std::vector<double>{0.0}, q1, 0.3, 0.7), Error);
  EXPECT_THROW(torque_feasible_duration(chain, home, Eigen::VectorXd::Zero(3), 0.3, 0.7), Error);
  EXPECT_THROW(torque_feasible_duration(chain, home, q1, 0.0, 0.7), Error);
  EXPECT_THROW(torque_feasible_duration(chain, home, q1, 0.3, 0.0), Error);
  EXPECT_THROW(torque_feasible_duration(chain, home, q1, 0.3, 1.5), Error);
  // a budget smaller than gravity alone
  const std::string why = [&] {
    try {
      torque_feasible_duration(chain, home, q1, 0.3, 0.01);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_NE(why.find("shoulder"), std::string::npos) << why;
}

}  // namespace
}  // namespace mjarm
