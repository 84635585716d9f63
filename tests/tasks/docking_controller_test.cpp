#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ik/malloc_counter.hpp"
#include "mjarm/tasks/docking/controller.hpp"
#include "mjarm/tasks/docking/task.hpp"
#include "support/error_message.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::contains;
using test::error_of;
using test::kDockingDeg;

const DockingScene& plain_scene() {
  static const DockingScene s = build_docking_scene();
  return s;
}

/// A state of @p scene at @p q with velocity @p qd, forwarded with the motors holding the bias
/// forces (so q̈ = 0 and the sensor reads the peg's weight only); its reference holds E there.
struct State {
  DataPtr d;
  Reference reference;
  State(const DockingScene& scene, const Eigen::VectorXd& q, const Eigen::VectorXd& qd)
      : d(scene.robot.make_data()) {
    scene.chain.scatter(q, d->qpos);
    for (int i = 0; i < 7; ++i) d->qvel[scene.chain.dof_address(i)] = qd[i];
    mj_forward(&scene.robot.model(), d.get());
    for (int i = 0; i < 7; ++i)
      d->ctrl[*scene.chain.actuator(i)] = d->qfrc_bias[scene.chain.dof_address(i)];
    mj_forward(&scene.robot.model(), d.get());
    const int tip = scene.robot.site(DockingNames::tip);
    reference.task.X_WE.p = Eigen::Map<const Eigen::Vector3d>(d->site_xpos + 3 * tip);
    reference.task.X_WE.R =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->site_xmat + 9 * tip);
    reference.joint.q = q;
    reference.joint.qd = Eigen::VectorXd::Zero(7);
    reference.joint.qdd = Eigen::VectorXd::Zero(7);
  }
};

Eigen::VectorXd start_q() { return plan_docking(plain_scene(), {}, {}).q_start; }

TEST(DockingController, LawsByNameAndTheirChoices) {
  EXPECT_EQ(docking_law("se3"), DockingLaw::se3);
  EXPECT_EQ(docking_law("cic"), DockingLaw::cic);
  EXPECT_EQ(docking_law("hqp-ac"), DockingLaw::hqp_ac);
  EXPECT_TRUE(contains(error_of([] { docking_law("osc"); }), "controllers: cic, hqp-ac, se3"));
  EXPECT_EQ(docking_laws().size(), 3u);
}

TEST(DockingController, AMissingForceTorqueSensorNamesTheSite) {
  DockingSceneOptions options;
  options.ft_sensor = false;
  const DockingScene scene = build_docking_scene(options);
  for (const DockingLaw law : docking_laws()) {
    DockingControllerOptions o;
    o.law = law;
    o.source = ForceSource::sensor;
    const std::string message = error_of([&] { DockingController(scene, o); });
    EXPECT_TRUE(contains(message, "site 'iiwa/peg/ft'")) << message;
    EXPECT_TRUE(contains(message, "no force sensor")) << message;
    o.source = ForceSource::observer;  // sensorless needs no sensor
    EXPECT_NO_THROW(DockingController(scene, o));
  }
}

TEST(DockingController, ANonFiniteSensorReadingIsSkippedCountedAndNeverReachesTheTorque) {
  DockingControllerOptions o;
  o.sensor_cutoff = std::numeric_limits<double>::infinity();
  DockingController controller(plain_scene(), o);
  State s(plain_scene(), start_q(), Eigen::VectorXd::Zero(7));
  JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  controller.compute(*s.d, s.reference, command);
  ASSERT_EQ(controller.bad_wrench_ticks(), 0);
  const Vector6d before = controller.measured_wrench();
  EXPECT_LT(before.norm(), 1e-6);  // the peg's weight is taken out: nothing touches it
  const int force = mj_name2id(&plain_scene().robot.model(), mjOBJ_SENSOR, DockingNames::force);
  const int torque = mj_name2id(&plain_scene().robot.model(), mjOBJ_SENSOR, DockingNames::torque);
  const int adr[2] = {plain_scene().robot.model().sensor_adr[force],
                      plain_scene().robot.model().sensor_adr[torque]};
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    for (const int a : adr) {
      const double kept = s.d->sensordata[a + 1];
      s.d->sensordata[a + 1] = bad;
      controller.compute(*s.d, s.reference, command);
      EXPECT_TRUE(command.value.allFinite());
      EXPECT_TRUE(controller.measured_wrench().allFinite());
      EXPECT_EQ(controller.measured_wrench(), before);  // the last good value is kept
      s.d->sensordata[a + 1] = kept;
    }
  }
  EXPECT_EQ(controller.bad_wrench_ticks(), 4);
  const auto names = controller.internal_names();
  const auto values = controller.internal_values();
  const auto it = std::find(names.begin(), names.end(), "bad_wrench_ticks");
  ASSERT_NE(it, names.end());
  EXPECT_EQ(values[static_cast<std::size_t>(it - names.begin())], 4.0);
}

TEST(DockingController, BadOptionsAreNamed) {
  auto message = [](auto edit) {
    DockingControllerOptions o;
    edit(o);
    return error_of([&] { DockingController(plain_scene(), o); });
  };
  EXPECT_TRUE(contains(message([](auto& o) { o.se3_stiffness[2] = -1.0; }), "se3_stiffness[2]"));
  EXPECT_TRUE(contains(message([](auto& o) { o.se3_inertia[4] = 0.0; }), "se3_inertia[4]"));
  EXPECT_TRUE(
      contains(message([](auto& o) { o.cic_stiffness[0] = std::nan(""); }), "cic_stiffness[0]"));
  EXPECT_TRUE(contains(message([](auto& o) { o.sensor_cutoff = 0.0; }), "sensor_cutoff"));
  EXPECT_TRUE(contains(message([](auto& o) { o.release_force = -2.0; }), "release_force"));
  EXPECT_TRUE(contains(message([](auto& o) { o.nullspace_damping = -1.0; }), "nullspace_damping"));
  EXPECT_TRUE(contains(message([](auto& o) { o.control_period = 0.0; }), "control_period"));
  EXPECT_TRUE(contains(message([](auto& o) { o.hqp_stiffness[3] = 0.0; }), "hqp_stiffness[3]"));
  EXPECT_TRUE(contains(message([](auto& o) { o.release_duration = 0.0; }), "release_duration"));
  const std::string rotational = message([](auto& o) {
    o.law = DockingLaw::hqp_ac;
    o.release_axes[5] = true;
  });
  EXPECT_TRUE(contains(rotational, "translational axes only")) << rotational;
}

TEST(DockingController, ANonFiniteReadingNeverReachesTheTorqueOfCicOrHqpAc) {
  const mjModel& m = plain_scene().robot.model();
  const int force = m.sensor_adr[mj_name2id(&m, mjOBJ_SENSOR, DockingNames::force)];
  for (const DockingLaw law : {DockingLaw::cic, DockingLaw::hqp_ac}) {
    DockingControllerOptions o;
    o.law = law;
    DockingController controller(plain_scene(), o);
    State s(plain_scene(), start_q(), Eigen::VectorXd::Zero(7));
    JointCommand good{CommandKind::torque, Eigen::VectorXd::Zero(7)};
    controller.compute(*s.d, s.reference, good);
    JointCommand command = good;
    for (const double bad : {std::nan(""), -std::numeric_limits<double>::infinity()}) {
      s.d->sensordata[force] = bad;
      controller.compute(*s.d, s.reference, command);
      EXPECT_TRUE(command.value.allFinite()) << to_string(law);
      EXPECT_TRUE(controller.measured_wrench().allFinite()) << to_string(law);
      // taken as zero: at rest the torque is the one of a good reading (the peg's weight out)
      EXPECT_LT((command.value - good.value).norm(), 1e-6) << to_string(law);
    }
    EXPECT_EQ(controller.bad_wrench_ticks(), 2) << to_string(law);
  }
}

TEST(DockingController, HqpAcGetsThePreloadAsItsOwnForceTermThroughTheTarget) {
  DockingControllerOptions o;
  o.law = DockingLaw::hqp_ac;
  o.source = ForceSource::observer;
  DockingController with(plain_scene(), o), without(plain_scene(), o);
  State s(plain_scene(), start_q(), Eigen::VectorXd::Zero(7));
  JointCommand a{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  JointCommand b = a;
  without.compute(*s.d, s.reference, b);
  s.reference.task.F_ext << 0.0, 0.0, -5.0, 0.0, 0.0, 0.0;
  with.compute(*s.d, s.reference, a);
  // Λ⁻¹ = J·M⁻¹·Jᵀ from MuJoCo directly (the tip site's Jacobian, the dense mass matrix)
  const mjModel& m = plain_scene().robot.model();
  Eigen::MatrixXd M(m.nv, m.nv), Jp(3, m.nv), Jr(3, m.nv);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Mr(m.nv, m.nv),
      jp(3, m.nv), jr(3, m.nv);
  mj_fullM(&m, s.d.get(), Mr.data());
  mj_jacSite(&m, s.d.get(), jp.data(), jr.data(), mj_name2id(&m, mjOBJ_SITE, DockingNames::tip));
  Eigen::MatrixXd J(6, m.nv);
  J << jp, jr;
  M = Mr;
  const Matrix6d Lambda_inv = J * M.ldlt().solve(J.transpose());
  const Vector6d expected = Lambda_inv * s.reference.task.F_ext;
  const Vector6d got = with.hqp_ac()->target() - without.hqp_ac()->target();
  EXPECT_LT((got - expected).norm(), 1e-9 * expected.norm()) << got.transpose();
  EXPECT_LT(expected.head<3>().dot(Eigen::Vector3d::UnitZ()), 0.0);  // it accelerates E down
  // τ changes by Jᵀ·F_ext when no bound is active (the main QP is exact, ε aside)
  const Eigen::VectorXd dtau = a.value - b.value;
  EXPECT_LT((dtau - J.transpose() * s.reference.task.F_ext).norm(), 1e-3) << dtau.transpose();
}

TEST(DockingController, HqpAcReleasesTheLateralAxesOnContact) {
  DockingControllerOptions o;
  o.law = DockingLaw::hqp_ac;
  o.sensor_cutoff = std::numeric_limits<double>::infinity();
  DockingController controller(plain_scene(), o);
  State s(plain_scene(), start_q(), Eigen::VectorXd::Zero(7));
  s.reference.task.X_WE.p += Eigen::Vector3d(0.004, -0.003, 0.002);  // 5 mm aside, 2 mm up
  JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  controller.compute(*s.d, s.reference, command);
  const double K0 = o.hqp_stiffness[0];
  EXPECT_NEAR(controller.stiffness()[0], 0.5 * K0, 1e-9);  // free space: K_r = K0/2
  // a 6 N push upwards on the peg (the sensor reads its opposite, plus the weight it carries)
  const mjModel& m = plain_scene().robot.model();
  const int force = m.sensor_adr[mj_name2id(&m, mjOBJ_SENSOR, DockingNames::force)];
  const int site = m.sensor_objid[mj_name2id(&m, mjOBJ_SENSOR, DockingNames::force)];
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R_WS(s.d->site_xmat +
                                                                            9 * site);
  const Eigen::Vector3d reading = Eigen::Map<const Eigen::Vector3d>(s.d->sensordata + force);
  const Eigen::Vector3d push = R_WS.transpose() * Eigen::Vector3d(0.0, 0.0, 6.0);
  Eigen::Map<Eigen::Vector3d>(s.d->sensordata + force) = reading - push;
  const int ticks = static_cast<int>(std::lround(o.release_duration / 0.002)) + 2;
  for (int k = 0; k < ticks; ++k) {
    s.d->time += 0.002;
    controller.compute(*s.d, s.reference, command);
  }
  EXPECT_GT(controller.measured_wrench()[2], 5.9);
  // released: no stiffness on E's x, y (world x, y with the peg pointing down), K_r on z
  EXPECT_LT(controller.stiffness().head<2>().norm(), 1e-9);
  EXPECT_NEAR(controller.stiffness()[2], controller.hqp_ac()->compliance().stiffness()(2, 2), 1e-9);
  // the law's position error is the vertical 2 mm only
  const auto names = controller.hqp_ac()->internal_names();
  const auto values = controller.hqp_ac()->internal_values();
  const auto it = std::find(names.begin(), names.end(), "position_error");
  ASSERT_NE(it, names.end());
  EXPECT_NEAR(values[static_cast<std::size_t>(it - names.begin())], 0.002, 1e-6);
  EXPECT_TRUE(command.value.allFinite());
  // reset forgets the release
  controller.reset();
  s.d->time = 0.0;
  Eigen::Map<Eigen::Vector3d>(s.d->sensordata + force) = reading;
  controller.compute(*s.d, s.reference, command);
  EXPECT_NEAR(controller.stiffness()[0], 0.5 * K0, 1e-9);
}

TEST(DockingController, ThePreloadShiftsTheSe3TargetByForceOverStiffness) {
  DockingControllerOptions o;
  o.source = ForceSource::observer;
  DockingController controller(plain_scene(), o);
  State s(plain_scene(), start_q(), Eigen::VectorXd::Zero(7));
  s.reference.task.F_ext.head<3>() = Eigen::Vector3d(0.0, 0.0, -5.0);  // push down with 5 N
  JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  controller.compute(*s.d, s.reference, command);
  // λ in E's axes: E's z points down, so the target is 5 N / K_z below E
  const Vector6d& lambda = controller.se3()->error();
  EXPECT_NEAR(lambda[2], 5.0 / o.se3_stiffness[2], 1e-12);
  EXPECT_LT(lambda.head<2>().norm() + lambda.tail<3>().norm(), 1e-12);
}

TEST(DockingController, TheFrictionFeedForwardAddsExactlyTheModelsFrictionAlongTheVelocity) {
  DockingSceneOptions options;
  options.joint_friction = true;
  const DockingScene scene = build_docking_scene(options);
  Eigen::VectorXd qd(7);
  qd << 0.02, -0.01, 0.005, 0.0, -0.3, 0.001, 0.05;
  State s(scene, start_q(), qd);
  JointCommand with{CommandKind::torque, Eigen::VectorXd::Zero(7)};
  JointCommand without = with;
  DockingControllerOptions o;
  DockingController a(scene, o);
  o.friction_feed_forward = false;
  DockingController b(scene, o);
  a.compute(*s.d, s.reference, with);
  b.compute(*s.d, s.reference, without);
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(with.value[i] - without.value[i],
                kFrankaFrictionLoss[static_cast<std::size_t>(i)] * std::tanh(qd[i] / 0.01), 1e-9)
        << i;
  // on the plain model the feed-forward is an exact no-op
  State plain(plain_scene(), start_q(), qd);
  DockingController c(plain_scene(), o);
  o.friction_feed_forward = true;
  DockingController e(plain_scene(), o);
  c.compute(*plain.d, plain.reference, with);
  e.compute(*plain.d, plain.reference, without);
  EXPECT_EQ(with.value, without.value);
}

TEST(DockingController, ComputeAllocatesNothing) {
  for (const ForceSource source : {ForceSource::sensor, ForceSource::observer}) {
    for (const DockingLaw law : docking_laws()) {
      DockingControllerOptions o;
      o.law = law;
      o.source = source;
      o.release_force = 1e-9;  // hqp-ac: the release path runs too
      DockingController controller(plain_scene(), o);
      State s(plain_scene(), start_q(), Eigen::VectorXd::Constant(7, 0.01));
      s.reference.task.F_ext[2] = -3.0;
      JointCommand command{CommandKind::torque, Eigen::VectorXd::Zero(7)};
      controller.compute(*s.d, s.reference, command);
      const std::uint64_t before = test::malloc_calls();
      for (int k = 0; k < 10; ++k) {
        s.d->time += 0.002;
        controller.compute(*s.d, s.reference, command);
        controller.internal_values();
      }
      EXPECT_EQ(test::malloc_calls() - before, 0u) << to_string(law) << " " << to_string(source);
      EXPECT_TRUE(command.value.allFinite());
    }
  }
}

}  // namespace
}  // namespace mjarm
