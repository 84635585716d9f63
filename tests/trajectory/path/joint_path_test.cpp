#include "mjarm/trajectory/path/joint_path.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/random.hpp"

namespace mjarm {
namespace {

std::vector<Eigen::VectorXd> joint_path_zigzag() {
  std::vector<Eigen::VectorXd> w(5, Eigen::VectorXd(3));
  w[0] << 0.0, 0.0, 0.0;
  w[1] << 1.0, 0.5, -0.2;
  w[2] << 1.5, -0.5, 0.3;
  w[3] << 0.7, -1.0, 1.0;
  w[4] << 0.2, 0.1, 1.4;
  return w;
}

std::string joint_path_error(const std::vector<Eigen::VectorXd>& w) {
  try {
    const JointPath path(w);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(JointPath, PassesEveryWaypointAtItsChordLength) {
  const auto w = joint_path_zigzag();
  const JointPath path(w);
  EXPECT_EQ(path.dofs(), 3);
  EXPECT_EQ(path.waypoint_count(), 5);
  Eigen::VectorXd q(3), dq(3), ddq(3);
  double s = 0.0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (k > 0) s += (w[k] - w[k - 1]).norm();
    EXPECT_NEAR(path.knots()[static_cast<Eigen::Index>(k)], s, 1e-12);
    path.evaluate(s, q, dq, ddq);
    EXPECT_LT((q - w[k]).norm(), 1e-12) << "waypoint " << k;
  }
  EXPECT_NEAR(path.length(), s, 1e-12);
}

TEST(JointPath, IsTwiceContinuouslyDifferentiableWithNaturalEnds) {
  const JointPath path(joint_path_zigzag());
  Eigen::VectorXd q(3), d1(3), d2(3), q_a(3), d1_a(3), d2_a(3), q_b(3), d1_b(3), d2_b(3);
  for (int k = 1; k + 1 < path.waypoint_count(); ++k) {
    const double s = path.knots()[k];
    path.evaluate(s - 1e-9, q_a, d1_a, d2_a);
    path.evaluate(s + 1e-9, q_b, d1_b, d2_b);
    EXPECT_LT((d1_a - d1_b).norm(), 1e-7) << "q′ at knot " << k;
    EXPECT_LT((d2_a - d2_b).norm(), 1e-7) << "q″ at knot " << k;
  }
  path.evaluate(0.0, q, d1, d2);
  EXPECT_LT(d2.norm(), 1e-12);
  path.evaluate(path.length(), q, d1, d2);
  EXPECT_LT(d2.norm(), 1e-12);
}

TEST(JointPath, DerivativesMatchFiniteDifferences) {
  const JointPath path(joint_path_zigzag());
  Eigen::VectorXd q(3), d1(3), d2(3), d3(3), qp(3), d1p(3), d2p(3), qm(3), d1m(3), d2m(3);
  Random rng(7);
  const double h = 1e-5;
  for (int trial = 0; trial < 50; ++trial) {
    const double s = uniform(rng, h, path.length() - h);
    path.evaluate(s, q, d1, d2, d3);
    path.evaluate(s + h, qp, d1p, d2p);
    path.evaluate(s - h, qm, d1m, d2m);
    EXPECT_LT((d1 - (qp - qm) / (2 * h)).norm(), 1e-7) << "s = " << s;
    EXPECT_LT((d2 - (d1p - d1m) / (2 * h)).norm(), 1e-6) << "s = " << s;
    if (path.piece_at(s - h) == path.piece_at(s + h))
      EXPECT_LT((d3 - (d2p - d2m) / (2 * h)).norm(), 1e-5) << "s = " << s;
  }
}

TEST(JointPath, TwoWaypointsMakeAStraightLineAtUnitSpeed) {
  Eigen::VectorXd a(2), b(2);
  a << 1.0, -1.0;
  b << 4.0, 3.0;
  const JointPath path({a, b});
  EXPECT_DOUBLE_EQ(path.length(), 5.0);
  Eigen::VectorXd q(2), d1(2), d2(2);
  path.evaluate(2.5, q, d1, d2);
  EXPECT_LT((q - 0.5 * (a + b)).norm(), 1e-12);
  EXPECT_LT((d1 - (b - a) / 5.0).norm(), 1e-12);
  EXPECT_LT(d2.norm(), 1e-12);
}

TEST(JointPath, RejectsBadWaypointsNamingThem) {
  auto w = joint_path_zigzag();
  EXPECT_NE(joint_path_error({w[0]}).find("at least 2 waypoints"), std::string::npos);
  auto nan = w;
  nan[2][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(joint_path_error(nan).find("waypoint 2 joint 1 is not finite"), std::string::npos);
  auto duplicate = w;
  duplicate[3] = duplicate[2];
  EXPECT_NE(joint_path_error(duplicate).find("waypoints 2 and 3 are the same"), std::string::npos);
  auto sizes = w;
  sizes[4] = Eigen::VectorXd::Zero(2);
  EXPECT_NE(joint_path_error(sizes).find("waypoint 4 has 2 joints"), std::string::npos);
  EXPECT_NE(joint_path_error({Eigen::VectorXd(), Eigen::VectorXd()}).find("no joints"),
            std::string::npos);
  const JointPath path(w);
  Eigen::VectorXd q(3), d1(2), d2(3);
  EXPECT_THROW(path.evaluate(0.1, q, d1, d2), Error);
}

}  // namespace
}  // namespace mjarm
