#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/kinematics/contacts.hpp"
#include "mjarm/sim/contact_query.hpp"
#include "mjarm/tasks/docking/monitor.hpp"
#include "mjarm/tasks/docking/task.hpp"
#include "support/error_message.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::contains;
using test::error_of;
using test::kDockingDeg;

constexpr double kDepth = 0.050;

/// The socket at (0.6, 0, 0.2), z up; E seated at depth @p depth with the peg pointing down.
DockingGoal goal() { return {Pose{Eigen::Matrix3d::Identity(), {0.6, 0.0, 0.2}}, kDepth}; }

Pose tip_at(double depth, double lateral_x, double tilt) {
  Pose X;
  // R_y(π) (peg down), then tilted by `tilt` about x
  X.R = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()).toRotationMatrix() *
        Eigen::Vector3d(-1.0, 1.0, -1.0).asDiagonal();
  X.p = goal().X_WS.p + Eigen::Vector3d(lateral_x, 0.0, -depth);
  return X;
}

/// A run of @p duration seconds at 2 ms: free motion until @p contact_time, then seated and
/// pressing with @p axial newtons.
std::vector<DockingSample> seated_run(double duration = 3.0, double contact_time = 1.0,
                                      double axial = 5.0) {
  std::vector<DockingSample> samples;
  for (int k = 0; k * 0.002 <= duration + 1e-9; ++k) {
    DockingSample s;
    s.t = k * 0.002;
    const bool touching = s.t >= contact_time;
    s.X_WE = tip_at(touching ? kDepth : 0.0, 0.0, 0.0);
    s.X_WD = s.X_WE;
    s.contacts = touching ? 4 : 0;
    s.F_peg.head<3>() = Eigen::Vector3d(0.0, 0.0, touching ? axial : 0.0);  // the socket pushes up
    s.manipulability = 0.1;
    s.joint_position_ratio = 0.5;
    s.joint_velocity_ratio = 0.1;
    samples.push_back(s);
  }
  return samples;
}

bool has(const std::vector<std::string>& failures, const std::string& why) {
  return std::find(failures.begin(), failures.end(), why) != failures.end();
}

TEST(DockingMonitor, ASeatedRunPassesAndItsFiguresAreThoseBuiltIn) {
  const auto samples = seated_run();
  const DockingMetrics m = evaluate_docking(samples, goal());
  EXPECT_TRUE(m.seated) << (m.failures.empty() ? "" : m.failures.front());
  EXPECT_EQ(m.samples, static_cast<int>(samples.size()));
  EXPECT_NEAR(m.steady_axial_force, 5.0, 1e-12);
  EXPECT_NEAR(m.peak_axial_force, 5.0, 1e-12);
  EXPECT_NEAR(m.peak_force, 5.0, 1e-12);
  EXPECT_NEAR(m.min_depth, kDepth, 1e-12);
  EXPECT_NEAR(m.max_lateral, 0.0, 1e-12);
  EXPECT_NEAR(m.max_tilt, 0.0, 1e-7);
  EXPECT_DOUBLE_EQ(m.contact_fraction, 1.0);
  EXPECT_NEAR(m.first_contact_time, 1.0, 1e-9);
  EXPECT_EQ(m.free_samples, 500);  // 0 … 0.998 s
  EXPECT_DOUBLE_EQ(m.max_joint_position, 50.0);
  EXPECT_DOUBLE_EQ(m.max_joint_velocity, 10.0);
  EXPECT_DOUBLE_EQ(m.min_manipulability, 0.1);
}

TEST(DockingMonitor, RmsIsTakenOverTheFreeMotionOnly) {
  auto samples = seated_run();
  // 1 mm and 0.1° off the reference before contact, 5 mm after (ignored)
  for (DockingSample& s : samples) {
    const bool free = s.contacts == 0;
    s.X_WD.p = s.X_WE.p + Eigen::Vector3d(free ? 1e-3 : 5e-3, 0.0, 0.0);
    s.X_WD.R = s.X_WE.R * Eigen::AngleAxisd(free ? 0.1 * kDockingDeg : 2.0 * kDockingDeg,
                                            Eigen::Vector3d::UnitZ())
                              .toRotationMatrix();
  }
  const DockingMetrics m = evaluate_docking(samples, goal());
  EXPECT_NEAR(m.position_rms, 1e-3, 1e-12);
  EXPECT_NEAR(m.orientation_rms, 0.1 * kDockingDeg, 1e-12);
}

TEST(DockingMonitor, LateralTiltAndDepthAreMeasuredFromTheTrueSocket) {
  auto samples = seated_run();
  for (DockingSample& s : samples)
    if (s.contacts > 0) s.X_WE = tip_at(kDepth - 0.4e-3, 0.3e-3, 0.2 * kDockingDeg);
  const DockingMetrics m = evaluate_docking(samples, goal());
  EXPECT_NEAR(m.max_lateral, 0.3e-3, 1e-12);
  EXPECT_NEAR(m.steady_lateral, 0.3e-3, 1e-12);
  EXPECT_NEAR(m.max_tilt, 0.2 * kDockingDeg, 1e-9);
  EXPECT_NEAR(m.min_depth, kDepth - 0.4e-3, 1e-12);
  EXPECT_TRUE(m.seated);
}

TEST(DockingMonitor, EachCriterionFailsOnItsOwn) {
  const DockingGoal g = goal();
  const DockingCriteria c;
  auto check_fails = [&](auto edit, const std::string& why) {
    auto samples = seated_run();
    for (DockingSample& s : samples) edit(s);
    const DockingMetrics m = evaluate_docking(samples, g, c);
    EXPECT_FALSE(m.seated) << why;
    EXPECT_TRUE(has(m.failures, why)) << why;
    EXPECT_EQ(m.failures.size(), 1u) << why << ": " << m.failures.front();
  };
  check_fails(
      [](DockingSample& s) {
        if (s.contacts) s.X_WE = tip_at(kDepth - 1.5e-3, 0, 0);
      },
      "depth");
  check_fails(
      [](DockingSample& s) {
        if (s.contacts) s.X_WE = tip_at(kDepth, 0.6e-3, 0);
      },
      "lateral");
  check_fails(
      [](DockingSample& s) {
        if (s.contacts) s.X_WE = tip_at(kDepth, 0, 0.6 * kDockingDeg);
      },
      "tilt");
  check_fails(
      [](DockingSample& s) {
        if (s.t > 2.5) s.V_WE[2] = -4e-3;
      },
      "not_settled");
  check_fails(
      [](DockingSample& s) {
        if (s.t > 2.5) s.V_WE[5] = 3.0 * kDockingDeg;
      },
      "not_settled");
  check_fails(
      [](DockingSample& s) {
        if (s.t > 2.9) s.contacts = 0;
      },
      "contact");
  check_fails(
      [](DockingSample& s) {
        if (s.t == 1.5) s.F_peg[0] = 41.0;
      },
      "force");
  check_fails(
      [](DockingSample& s) {
        if (s.t > 1.5 && s.t < 1.6) s.F_peg[5] = 2.5;
      },
      "axial_moment");
  check_fails(
      [](DockingSample& s) {
        if (s.t < 0.04) s.saturated = true;
      },
      "saturation");
  check_fails(
      [](DockingSample& s) {
        if (s.t == 0.5) s.within_limits = false;
      },
      "joint_limit");
  check_fails(
      [](DockingSample& s) {
        if (s.t == 0.5) {
          s.other_contact = true;
          s.other_geom1 = 3;
          s.other_geom2 = 7;
        }
      },
      "other_contact");
  check_fails(
      [](DockingSample& s) {
        if (s.t == 0.5) s.finite = false;
      },
      "non_finite");
}

TEST(DockingMonitor, ThresholdsAreInclusiveAndSaturationCountsTicks) {
  auto samples = seated_run();
  int n = 0;
  for (DockingSample& s : samples)
    if (n++ < static_cast<int>(samples.size()) / 100) s.saturated = true;  // exactly 1 %
  samples[1000].F_peg[0] = 40.0;
  const DockingMetrics m = evaluate_docking(samples, goal());
  EXPECT_LE(m.saturation, 0.01);
  EXPECT_NEAR(m.peak_force, std::hypot(40.0, 5.0), 1e-12);
  EXPECT_TRUE(has(m.failures, "force"));  // ‖(40, 0, 5)‖ > 40
  EXPECT_FALSE(has(m.failures, "saturation"));
}

TEST(DockingMonitor, AShortOrEmptyRunFails) {
  EXPECT_TRUE(has(evaluate_docking({}, goal()).failures, "too_short"));
  const auto samples = seated_run(0.5, 0.1);
  EXPECT_TRUE(has(evaluate_docking(samples, goal()).failures, "too_short"));
}

TEST(DockingMonitor, BadCriteriaAreNamed) {
  DockingCriteria c;
  c.max_lateral = -1.0;
  EXPECT_NE(error_of([&] { check(c); }).find("max_lateral"), std::string::npos);
  c = {};
  c.min_contact_fraction = 1.5;
  EXPECT_NE(error_of([&] { check(c); }).find("min_contact_fraction must be in (0, 1], got 1.5"),
            std::string::npos);
  c = {};
  c.window = std::nan("");
  EXPECT_NE(error_of([&] { evaluate_docking({}, goal(), c); }).find("window"), std::string::npos);
}

TEST(DockingProbe, ContactWrenchAgreesWithTheSimulationsContactQueries) {
  const DockingScene scene = build_docking_scene();
  const DockingPlan plan = plan_docking(scene, {0.003, 0.0, 0.0}, {});
  // the peg pushed 0.5 mm into the bottom and 0.2 mm into the wall, tilted a little
  Pose X = scene.seated();
  X.p += Eigen::Vector3d(0.7e-3, 0.0, -0.5e-3);
  X.R = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).toRotationMatrix() * X.R;
  const Robot& robot = scene.robot;
  PoseIk ik(scene.chain);
  const IkResult r = ik.solve(X, plan.q_start);
  ASSERT_EQ(r.status, IkStatus::converged);
  DataPtr d = robot.make_data();
  scene.chain.scatter(r.q, d->qpos);
  mj_forward(&robot.model(), d.get());
  DockingProbe probe(scene, iiwa14_max_velocity());
  DockingSample s;
  probe.sample(robot.model(), *d, 0.0, X, false, s);
  ASSERT_GT(s.contacts, 1);
  EXPECT_FALSE(s.other_contact);
  // force: the socket on the peg = minus the peg on the socket (contact_query, sim/)
  const ContactSummary summary = contact_between(robot.model(), *d, scene.peg, scene.socket);
  EXPECT_EQ(s.contacts, summary.contacts);
  EXPECT_LT((s.F_peg.head<3>() + summary.force_W).norm(), 1e-9);
  EXPECT_GT(s.F_peg[2], 1.0);  // the bottom pushes the peg up
  // moment about the tip: from the per-contact forces of kinematics/contacts
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  const int peg_body = scene.peg_body;
  for (const ContactForce& c : contact_forces(robot.model(), *d)) {
    const double sign = c.body2 == peg_body ? 1.0 : c.body1 == peg_body ? -1.0 : 0.0;
    moment += (c.position - s.X_WE.p).cross(sign * c.force_W);
  }
  EXPECT_LT((s.F_peg.tail<3>() - moment).norm(), 1e-9);
  EXPECT_TRUE(s.finite);
  EXPECT_TRUE(s.within_limits);
  EXPECT_GT(s.manipulability, 0.0);
}

TEST(DockingProbe, ContactsOtherThanPegAndSocketAreNamed) {
  const DockingScene scene = build_docking_scene();
  const DockingPlan plan = plan_docking(scene, {}, {});
  const Pose X = plan.X_start;
  DataPtr d = scene.robot.make_data();
  scene.chain.scatter(plan.q_start, d->qpos);
  d->qpos[scene.chain.qpos_address(1)] += 0.5;  // lean the arm forward, down onto the floor
  mj_forward(&scene.robot.model(), d.get());
  DockingProbe probe(scene, iiwa14_max_velocity());
  DockingSample s;
  probe.sample(scene.robot.model(), *d, 0.0, X, false, s);
  ASSERT_TRUE(s.other_contact);
  const std::string a = mj_id2name(&scene.robot.model(), mjOBJ_GEOM, s.other_geom1);
  const std::string b = mj_id2name(&scene.robot.model(), mjOBJ_GEOM, s.other_geom2);
  EXPECT_EQ(a, "arena/floor");
  EXPECT_EQ(b.rfind("iiwa/", 0), 0u) << b;
  EXPECT_EQ(s.contacts, 0);
}

TEST(DockingProbe, BadSpeedLimitsAreRefused) {
  const DockingScene scene = build_docking_scene();
  EXPECT_NE(error_of([&] { DockingProbe(scene, Eigen::VectorXd::Ones(6)); }).find("7 entries"),
            std::string::npos);
  Eigen::VectorXd v = iiwa14_max_velocity();
  v[3] = 0.0;
  EXPECT_NE(error_of([&] { DockingProbe(scene, v); }).find("iiwa/joint4"), std::string::npos);
}

}  // namespace
}  // namespace mjarm
