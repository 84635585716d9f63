#include "mjarm/tasks/docking_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ik/malloc_counter.hpp"
#include "mjarm/tasks/docking_task.hpp"
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
  for (const DockingLaw law : {DockingLaw::se3, DockingLaw::cic}) {
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
  EXPECT_TRUE(contains(message([](auto& o) { o.se3_stiffness[2] = -1.0; }), "se3_stiffness z"));
  EXPECT_TRUE(contains(message([](auto& o) { o.se3_inertia[4] = 0.0; }), "se3_inertia ry"));
  EXPECT_TRUE(
      contains(message([](auto& o) { o.cic_stiffness[0] = std::nan(""); }), "cic_stiffness x"));
  EXPECT_TRUE(contains(message([](auto& o) { o.sensor_cutoff = 0.0; }), "sensor_cutoff"));
  EXPECT_TRUE(contains(message([](auto& o) { o.release_force = -2.0; }), "release_force"));
  EXPECT_TRUE(contains(message([](auto& o) { o.nullspace_damping = -1.0; }), "nullspace_damping"));
  EXPECT_TRUE(contains(message([](auto& o) { o.control_period = 0.0; }), "control_period"));
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
    for (const DockingLaw law : {DockingLaw::se3, DockingLaw::cic}) {
      DockingControllerOptions o;
      o.law = law;
      o.source = source;
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
