#include "mjarm/control/wrench_source.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "control/compliance_test_support.hpp"
#include "control/task_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::Rig;
using test::VectorX;

/// The iiwa14 with the F/T tool at home, standing still: ctrl = qfrc_bias − Jᵀ·F_push holds it
/// against gravity and against @p push (world axes, at the tool tip), so qacc = 0 and the
/// sensor reads the statics exactly; mj_forward run (sensors current).
void ws_hold_still_under(Rig& rig, const Vector6d& push) {
  const mjModel& m = rig.m();
  mjData& d = rig.d();
  mj_resetDataKeyframe(&m, &d, rig.robot.keyframe("home"));
  mj_forward(&m, &d);
  const int tip = rig.chain.frame().id;
  const int body = m.site_bodyid[tip];
  const Pose X = test::site_pose(d, tip);
  test::push_body(m, d, body, push.head<3>(), X.p);
  for (int i = 0; i < 3; ++i) d.xfrc_applied[6 * body + 3 + i] += push[3 + i];
  const test::MatrixX J = test::site_jacobian(m, d, tip);
  const VectorX tau = Eigen::Map<const VectorX>(d.qfrc_bias, m.nv) - J.transpose() * push;
  for (int i = 0; i < rig.chain.size(); ++i) d.ctrl[*rig.chain.actuator(i)] = tau[i];
  mj_forward(&m, &d);
}

TEST(WrenchSource, SensorGivesThePushOnTheToolAboutE) {
  // the sensor reads −(push + the tool's weight) (moments about its site): the source turns it
  // into the push itself, in world axes about E (the tip), once the weight is taken out
  Rig rig(test::iiwa_ft_tool(), "tip");
  const Vector6d push = (Vector6d() << 3.0, -2.0, 7.5, 0.2, -0.1, 0.3).finished();
  ws_hold_still_under(rig, push);
  for (int i = 0; i < rig.m().nv; ++i) ASSERT_NEAR(rig.d().qacc[i], 0.0, 1e-8);
  WrenchSourceOptions o;
  o.kind = WrenchSourceKind::sensor;
  o.site = "ft";
  o.timing = SensorTiming::after_forward;
  WrenchSource source(rig.chain, o);
  const Pose X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  ASSERT_EQ(source.measure(rig.d(), X_WE), WrenchStatus::ok);
  EXPECT_LE((source.wrench() - push).norm(), 1e-9 * push.norm()) << source.wrench().transpose();
  EXPECT_EQ(source.time(), rig.d().time);
  // without the weight compensation the tool's weight (0.3 kg) shows
  o.compensate_tool_weight = false;
  WrenchSource raw(rig.chain, o);
  raw.measure(rig.d(), X_WE);
  EXPECT_NEAR(raw.wrench()[2] - push[2], -0.3 * 9.81, 1e-9);
  // one step old after mj_step (the default timing)
  o.compensate_tool_weight = true;
  o.timing = SensorTiming::after_step;
  WrenchSource stepped(rig.chain, o);
  stepped.measure(rig.d(), X_WE);
  EXPECT_DOUBLE_EQ(stepped.time(), rig.d().time - rig.m().opt.timestep);
}

TEST(WrenchSource, ObserverEstimatesThePushOnceSettled) {
  // the arm held by a joint PD with gravity compensation; a push on the tool tip from t = 0;
  // the observer, fed the motor torque each tick, converges to the push (world axes about E)
  Rig rig(test::iiwa_ft_tool(), "tip");
  const mjModel& m = rig.m();
  mjData& d = rig.d();
  mj_resetDataKeyframe(&m, &d, rig.robot.keyframe("home"));
  mj_forward(&m, &d);
  const int tip = rig.chain.frame().id;
  const Vector6d push = (Vector6d() << 6.0, -3.0, 4.0, 0.0, 0.0, 0.0).finished();
  WrenchSourceOptions o;
  o.kind = WrenchSourceKind::observer;
  WrenchSource source(rig.chain, o);
  ChainDynamics dyn(rig.chain);
  const VectorX q_home = rig.chain.gather(d.qpos);
  VectorX tau(7);
  for (int k = 0; k < 2000; ++k) {  // 4 s
    mj_step1(&m, &d);
    test::push_body(m, d, m.site_bodyid[tip], push.head<3>(), test::site_pose(d, tip).p);
    dyn.update(d);
    source.measure(d, dyn.pose());
    tau = dyn.bias() + 300.0 * (q_home - dyn.q()) - 30.0 * dyn.qd();
    test::apply_torque(rig.chain, tau, d);
    ASSERT_EQ(source.record_command(d, dyn, tau), ObserverStatus::ok);
    mj_step2(&m, &d);
  }
  // the estimate concerns the previous tick's state: one period old
  EXPECT_NEAR(source.time(), d.time - 2 * m.opt.timestep, 1e-12);
  EXPECT_LE((source.wrench() - push).norm(), 0.02 * push.norm()) << source.wrench().transpose();
}

TEST(WrenchSource, NoneIsZeroAndReadsAllocateNothing) {
  Rig rig(test::iiwa_ft_tool(), "tip");
  ws_hold_still_under(rig, Vector6d::Constant(1.0));
  const Pose X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  WrenchSource none(rig.chain);
  EXPECT_EQ(none.kind(), WrenchSourceKind::none);
  EXPECT_EQ(none.measure(rig.d(), X_WE), WrenchStatus::ok);
  EXPECT_EQ(none.wrench().norm(), 0.0);
  WrenchSourceOptions s;
  s.kind = WrenchSourceKind::sensor;
  s.site = "ft";
  WrenchSource sensor(rig.chain, s);
  WrenchSourceOptions b;
  b.kind = WrenchSourceKind::observer;
  WrenchSource observer(rig.chain, b);
  ChainDynamics dyn(rig.chain);
  dyn.update(rig.d());
  const VectorX tau = dyn.bias();
  observer.record_command(rig.d(), dyn, tau);
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 50; ++k) {
    rig.d().time += 0.002;
    sensor.measure(rig.d(), X_WE);
    observer.measure(rig.d(), X_WE);
    observer.record_command(rig.d(), dyn, tau);
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

TEST(WrenchSource, NonFiniteReadingIsZeroAndFlagged) {
  Rig rig(test::iiwa_ft_tool(), "tip");
  ws_hold_still_under(rig, Vector6d::Zero());
  WrenchSourceOptions o;
  o.kind = WrenchSourceKind::sensor;
  o.site = "ft";
  WrenchSource source(rig.chain, o);
  rig.d().sensordata[4] = NAN;
  const Pose X_WE = test::site_pose(rig.d(), rig.chain.frame().id);
  EXPECT_EQ(source.measure(rig.d(), X_WE), WrenchStatus::non_finite);
  EXPECT_EQ(source.status(), WrenchStatus::non_finite);
  EXPECT_EQ(source.wrench().norm(), 0.0);
  rig.d().sensordata[4] = 0.0;
  rig.d().sensordata[0] = INFINITY;
  EXPECT_EQ(source.measure(rig.d(), X_WE), WrenchStatus::non_finite);
}

TEST(WrenchSource, MissingSensorNamesTheSite) {
  // the bundled arm has no sensors at all; the tool model has them on "ft" only
  const Robot bare = Robot::bundled("iiwa14_torque");
  const Chain chain(bare, "attachment_site");
  WrenchSourceOptions o;
  o.kind = WrenchSourceKind::sensor;
  o.site = "attachment_site";
  const std::string missing = test::error_of([&] { WrenchSource s(chain, o); });
  EXPECT_NE(missing.find("site 'attachment_site'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("no force sensor"), std::string::npos) << missing;
  o.site = "flange_ft";
  const std::string unknown = test::error_of([&] { WrenchSource s(chain, o); });
  EXPECT_NE(unknown.find("flange_ft"), std::string::npos) << unknown;
  o.site = "";
  const std::string empty = test::error_of([&] { WrenchSource s(chain, o); });
  EXPECT_NE(empty, "(no error)");
  WrenchSourceOptions p;
  p.kind = WrenchSourceKind::observer;
  p.control_period = -1.0;
  EXPECT_NE(test::error_of([&] { WrenchSource s(chain, p); }).find("control_period"),
            std::string::npos);
  p.control_period = 0.0;
  p.observer.kp = 0.0;
  EXPECT_NE(test::error_of([&] { WrenchSource s(chain, p); }), "(no error)");
  EXPECT_STREQ(to_string(WrenchSourceKind::observer), "observer");
}

}  // namespace
}  // namespace mjarm
