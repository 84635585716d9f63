// HQP-AC's per-tick solve diagnostics and its preload's ramp-out when contact is lost.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "control/compliance_test_support.hpp"
#include "control/task_control_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/control/hqp_ac.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::Rig;
using test::VectorX;

const char* kHqpDiagTable =
    R"(<geom name="table" type="box" pos="0.62 0 0.1" size="0.2 0.2 0.1"/>)";

TEST(HqpAcDiagnostics, AreFilledAndPlausible) {
  // free space from home, then joint 4 driven at its upper limit (a position bound must become
  // active): the counts add up, the working sets fit their QPs, the time is positive
  Rig rig("iiwa14_torque", "attachment_site");
  mjData& d = rig.d();
  mj_resetDataKeyframe(&rig.m(), &d, rig.robot.keyframe("home"));
  mj_forward(&rig.m(), &d);
  const int n = rig.chain.size();
  HqpAcController c(rig.chain);
  Reference ref;
  ref.task.X_WE = test::site_pose(d, rig.chain.frame().id);
  ref.task.X_WE.p.x() += 0.05;
  JointCommand command{CommandKind::torque, VectorX::Zero(n)};
  auto check = [&](const char* what) {
    SCOPED_TRACE(what);
    const HqpAcSolveDiagnostics& g = c.solve_diagnostics();
    EXPECT_EQ(g.main_constraints, 2 * n);
    EXPECT_EQ(g.null_constraints, 6 + 2 * n);
    EXPECT_EQ(g.iterations, g.main_iterations + g.null_iterations);
    EXPECT_EQ(g.main_iterations, c.last_tick().main_iterations);
    EXPECT_EQ(g.null_iterations, c.last_tick().null_iterations);
    EXPECT_GE(g.main_active, 0);
    EXPECT_LE(g.main_active, std::min(g.main_constraints, n));
    EXPECT_LE(g.null_active, std::min(g.null_constraints, n));
    EXPECT_GT(g.solve_time_us, 0.0);
    EXPECT_EQ(c.internal_values()[12], g.main_active);
    EXPECT_EQ(c.internal_values()[13], g.null_active);
    std::printf(
        "hqp-ac solve, %s: iterations %d (main %d, null %d), active %d/%d and %d/%d, "
        "%.1f µs\n",
        what, g.iterations, g.main_iterations, g.null_iterations, g.main_active, g.main_constraints,
        g.null_active, g.null_constraints, g.solve_time_us);
  };
  c.compute(d, ref, command);
  ASSERT_EQ(c.status(), HqpAcStatus::ok);
  EXPECT_GE(c.solve_diagnostics().iterations, 1);  // the cold first solve
  check("free space");
  d.qpos[rig.chain.qpos_address(3)] = rig.chain.upper()[3] - 1e-3;
  d.qvel[rig.chain.dof_address(3)] = 1.0;  // towards the limit
  mj_forward(&rig.m(), &d);
  c.compute(d, ref, command);
  ASSERT_TRUE(c.status() == HqpAcStatus::ok || c.status() == HqpAcStatus::damped);
  EXPECT_GE(c.solve_diagnostics().main_iterations, 1);
  EXPECT_GE(c.solve_diagnostics().main_active, 1);  // the position bound of joint 4
  check("at a limit");
  // the hold command runs no QP: all zero
  Reference bad = ref;
  bad.task.X_WE.p.x() = NAN;
  c.compute(d, bad, command);
  EXPECT_EQ(c.solve_diagnostics().iterations, 0);
  EXPECT_EQ(c.solve_diagnostics().solve_time_us, 0.0);
  // the diagnostics cost no allocation
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 20; ++k) {
    d.time += 0.002;
    c.compute(d, ref, command);
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

TEST(HqpAcDiagnostics, PreloadRampsOutWhenContactIsLost) {
  // the tool pressed 2 mm into a table with a 5 N preload (as PreloadIsReachedInContact, with a
  // stiffer z), then
  // the target lifted 5 cm: once contact is lost the preload falls monotonically to 0 within
  // release_time, instead of staying latched at P
  Rig rig(test::iiwa_ft_tool({}, kHqpDiagTable), "tip");
  const mjModel& m = rig.m();
  mjData& d = rig.d();
  mj_resetDataKeyframe(&m, &d, rig.robot.keyframe("home"));
  mj_forward(&m, &d);
  HqpAcOptions o;
  // K0_z = 1000 N/m: lifted 5 cm, the spring (≥ 0.3·K0_z·5 cm = 15 N) beats the 5 N preload
  o.compliance.stiffness = (Vector6d() << 1500, 1500, 1000, 150, 150, 150).finished().asDiagonal();
  o.preload.force = 5.0;
  o.preload.contact_force = 0.5;
  o.preload.release_time = 0.2;
  o.force.kind = WrenchSourceKind::sensor;
  o.force.site = "ft";
  HqpAcController c(rig.chain, o);
  Reference ref;
  ref.task.X_WE = test::site_pose(d, rig.chain.frame().id);
  ref.task.X_WE.p.z() = 0.198;
  JointCommand command{CommandKind::torque, VectorX::Zero(7)};
  auto tick = [&] {
    mj_step1(&m, &d);
    c.compute(d, ref, command);
    test::apply_torque(rig.chain, command.value, d);
    mj_step2(&m, &d);
  };
  for (int k = 0; k < 1500; ++k) tick();  // 3 s: in contact, the preload fully in
  ASSERT_TRUE(c.last_tick().in_contact);
  ASSERT_NEAR(c.preload_force().norm(), 5.0, 1e-9);
  ref.task.X_WE.p.z() += 0.05;
  double lost = -1.0, zero = -1.0, previous = 5.0;
  int rises = 0;
  for (int k = 0; k < 1000; ++k) {
    tick();
    const double p = c.preload_force().norm();
    if (lost < 0.0 && !c.last_tick().in_contact) lost = d.time;
    if (lost >= 0.0) {
      if (p > previous + 1e-12) ++rises;
      if (zero < 0.0 && p == 0.0) zero = d.time;
    }
    previous = p;
  }
  std::printf(
      "hqp-ac preload after lift-off: contact lost at +%.3f s, preload 0 after %.3f s "
      "(release_time 0.2 s), %d rises\n",
      lost - 3.0, zero - lost, rises);
  ASSERT_GE(lost, 0.0);
  ASSERT_GE(zero, 0.0);
  EXPECT_EQ(rises, 0);
  EXPECT_LE(zero - lost, o.preload.release_time + 2.0 * m.opt.timestep);
  EXPECT_GE(zero - lost, o.preload.release_time - 2.0 * m.opt.timestep);  // a ramp, not a cut
  EXPECT_FALSE(c.last_tick().in_contact);
}

TEST(HqpAcDiagnostics, BadReleaseOptionsThrowNamingThem) {
  Rig rig("iiwa14_torque", "attachment_site");
  auto error = [&](auto edit) {
    HqpAcOptions o;
    edit(o);
    return test::error_of([&] { HqpAcController c(rig.chain, o); });
  };
  EXPECT_NE(error([](auto& o) { o.preload.release_time = 0.0; }).find("preload.release_time"),
            std::string::npos);
  EXPECT_NE(error([](auto& o) { o.preload.release_time = NAN; }).find("release_time"),
            std::string::npos);
  EXPECT_NE(error([](auto& o) { o.preload.release_ratio = 0.0; }).find("preload.release_ratio"),
            std::string::npos);
  EXPECT_NE(error([](auto& o) { o.preload.release_ratio = 1.5; }).find("release_ratio"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm
