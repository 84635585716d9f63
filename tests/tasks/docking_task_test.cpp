#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ik/malloc_counter.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/tasks/docking/task.hpp"
#include "support/error_message.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::contains;
using test::error_of;
using test::kDockingDeg;

const DockingScene& scene() {
  static const DockingScene s = build_docking_scene();
  return s;
}

/// The reference at @p t seconds after the first update (a fresh task each time).
Reference reference_at(DockingTask& task, mjData& d, double t0, double t) {
  Reference r;
  d.time = t0 + t;
  task.update(d, r);
  return r;
}

TEST(DockingPlan, PosesFollowTheTrueAndTheBelievedSocket) {
  const DockingOffset offset{0.006, -0.004, 15.0 * kDockingDeg};
  DockingMotion motion;
  const DockingPlan plan = plan_docking(scene(), offset, motion);
  const Pose& S = plan.X_WS;
  // the believed socket: shifted and yawed in the true socket's frame
  EXPECT_LT((plan.X_WB.p - (S.p + Eigen::Vector3d(0.006, -0.004, 0.0))).norm(), 1e-15);
  EXPECT_NEAR(so3::angle(S.R.transpose() * plan.X_WB.R), 15.0 * kDockingDeg, 1e-12);
  // start above the true socket, standoff above the believed one, seated in the believed one
  EXPECT_LT((plan.X_start.p - (S.p + Eigen::Vector3d(0.0, 0.0, motion.start_height))).norm(),
            1e-12);
  EXPECT_LT((plan.X_standoff.p - (plan.X_WB.p + Eigen::Vector3d(0, 0, motion.standoff))).norm(),
            1e-12);
  EXPECT_LT((plan.X_seated.p - (plan.X_WB.p - Eigen::Vector3d(0, 0, plan.full_depth))).norm(),
            1e-12);
  EXPECT_DOUBLE_EQ(plan.full_depth, 0.050);
  // the peg points down the believed axis
  EXPECT_LT((plan.X_seated.R.col(2) + plan.X_WB.R.col(2)).norm(), 1e-12);
  // the IK start puts E at X_start
  ChainKinematics kinematics(scene().chain);
  kinematics.update(plan.q_start);
  EXPECT_LT((kinematics.pose().p - plan.X_start.p).norm(), 1e-5);
  // the slow insertion: a trapezoid over standoff + depth
  EXPECT_NEAR(plan.insert_time,
              TrapezoidProfile(motion.standoff + 0.05, motion.insertion_speed,
                               motion.insertion_acceleration)
                  .duration(),
              1e-12);
  EXPECT_NEAR(plan.duration(), plan.approach_time + plan.insert_time + motion.hold_time, 1e-12);
}

TEST(DockingTask, TheReferenceIsContinuousAndItsVelocityIsTheRateOfItsPosition) {
  for (const DockingReference kind :
       {DockingReference::two_phase, DockingReference::single_segment}) {
    DockingMotion motion;
    motion.reference = kind;
    const DockingPlan plan = plan_docking(scene(), {0.006, 0.006, -15.0 * kDockingDeg}, motion);
    DataPtr d = scene().robot.make_data();
    DockingTask task(plan, motion);
    const double t0 = 1.25;
    reference_at(task, *d, t0, 0.0);
    const double h = 1e-6;
    for (double t = 0.05; t < plan.duration(); t += 0.173) {
      const Reference r = reference_at(task, *d, t0, t);
      const Reference a = reference_at(task, *d, t0, t - h);
      const Reference b = reference_at(task, *d, t0, t + h);
      const Eigen::Vector3d v = (b.task.X_WE.p - a.task.X_WE.p) / (2 * h);
      EXPECT_LT((r.task.V_WE.head<3>() - v).norm(), 1e-6) << to_string(kind) << " t " << t;
      const Eigen::Vector3d w = so3::log(b.task.X_WE.R * a.task.X_WE.R.transpose()) / (2 * h);
      EXPECT_LT((r.task.V_WE.tail<3>() - w).norm(), 1e-6) << to_string(kind) << " t " << t;
    }
    // the phase boundaries: no jump
    for (const double t : {plan.approach_time, plan.approach_time + plan.insert_time}) {
      const Reference a = reference_at(task, *d, t0, t - 1e-9);
      const Reference b = reference_at(task, *d, t0, t + 1e-9);
      EXPECT_LT((a.task.X_WE.p - b.task.X_WE.p).norm(), 1e-9);
      EXPECT_LT((a.task.V_WE - b.task.V_WE).norm(), 1e-6);
    }
    const Reference end = reference_at(task, *d, t0, plan.approach_time + plan.insert_time);
    EXPECT_TRUE(end.task.X_WE.is_approx(plan.X_seated, 1e-12));
    EXPECT_TRUE(end.task.V_WE.isZero(1e-12));
    EXPECT_EQ(end.joint.q, plan.q_start);
  }
}

TEST(DockingTask, PhasesAndThePreloadRampAlongTheBelievedAxis) {
  DockingMotion motion;
  motion.preload = 5.0;
  motion.preload_ramp = 0.4;
  const DockingPlan plan = plan_docking(scene(), {0.0, 0.0, 30.0 * kDockingDeg}, motion);
  DataPtr d = scene().robot.make_data();
  DockingTask task(plan, motion);
  Reference r;
  d->time = 0.0;
  EXPECT_TRUE(task.update(*d, r));
  EXPECT_EQ(task.phase(), DockingPhase::approach);
  EXPECT_TRUE(r.task.F_ext.isZero());
  d->time = plan.approach_time + 0.5;
  EXPECT_TRUE(task.update(*d, r));
  EXPECT_EQ(task.phase(), DockingPhase::insert);
  EXPECT_TRUE(r.task.F_ext.isZero());
  const double t_hold = plan.approach_time + plan.insert_time;
  d->time = t_hold + 0.1;
  EXPECT_TRUE(task.update(*d, r));
  EXPECT_EQ(task.phase(), DockingPhase::hold);
  EXPECT_LT((r.task.F_ext.head<3>() - Eigen::Vector3d(0.0, 0.0, -1.25)).norm(), 1e-9);
  EXPECT_TRUE(r.task.F_ext.tail<3>().isZero());
  d->time = t_hold + 1.0;
  EXPECT_TRUE(task.update(*d, r));
  EXPECT_NEAR(r.task.F_ext[2], -5.0, 1e-12);
  d->time = plan.duration();
  EXPECT_FALSE(task.update(*d, r));
}

TEST(DockingTask, UpdateAllocatesNothingAfterTheFirstTick) {
  DockingMotion motion;
  const DockingPlan plan = plan_docking(scene(), {0.003, 0.0, 0.0}, motion);
  DataPtr d = scene().robot.make_data();
  DockingTask task(plan, motion, 0.001);
  Reference r;
  task.update(*d, r);
  const std::uint64_t before = test::malloc_calls();
  for (double t = 0.0; t < plan.duration(); t += 0.01) {
    d->time = t;
    task.update(*d, r);
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

TEST(DockingTask, BadOffsetsAndMotionsAreNamed) {
  auto offset_error = [](DockingOffset o) {
    return error_of([&] { plan_docking(scene(), o, {}); });
  };
  EXPECT_TRUE(contains(offset_error({std::nan(""), 0.0, 0.0}), "dx and dy must be finite"));
  EXPECT_TRUE(contains(offset_error({0.0, 0.06, 0.0}), "±0.05 m"));
  EXPECT_TRUE(contains(offset_error({0.0, 0.0, 4.0}), "dyaw"));
  EXPECT_TRUE(contains(offset_error({0.0, 0.0, INFINITY}), "dyaw"));
  auto motion_error = [](auto edit) {
    DockingMotion m;
    edit(m);
    return error_of([&] { plan_docking(scene(), {}, m); });
  };
  EXPECT_TRUE(contains(motion_error([](auto& m) { m.standoff = 0.07; }), "standoff"));
  EXPECT_TRUE(contains(motion_error([](auto& m) { m.preload = -1.0; }), "preload"));
  EXPECT_TRUE(contains(motion_error([](auto& m) { m.hold_time = 0.0; }), "hold_time"));
  EXPECT_TRUE(
      contains(motion_error([](auto& m) { m.insertion_speed = std::nan(""); }), "insertion_speed"));
  EXPECT_TRUE(contains(error_of([] { docking_reference("double"); }), "two-phase, single"));
  DockingPlan empty;
  EXPECT_TRUE(contains(error_of([&] { DockingTask(empty, {}); }), "no start configuration"));
}

}  // namespace
}  // namespace mjarm
