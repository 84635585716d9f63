// PickPlaceTask on its own: the schedule and the segments' poses, the weld switched at the right
// instants, an allocation-free control loop, bad input.

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <vector>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "mjarm/sim/grasp_monitor.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/sim/weld_grasp.hpp"
#include "mjarm/tasks/pick_place/controllers.hpp"
#include "mjarm/tasks/pick_place/scene.hpp"
#include "mjarm/tasks/pick_place/task.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

// everything a task needs, as run_pick_place builds it
struct Rig {
  PickPlaceScene scene;
  Simulation sim;
  Chain arm;
  std::unique_ptr<Controller> arm_controller;
  std::unique_ptr<FingerForceController> fingers;
  std::optional<WeldGrasp> weld;
  std::optional<GraspMonitor> monitor;
  int table_watch = -1;
  PickPlaceGoal goal;

  Rig(SimulationMode mode, GraspKind grasp)
      : scene(build_pick_place_scene(scene_options(mode))),
        sim(scene.model, sim_options(mode)),
        arm(scene.model, scene.arm_joints, scene.tool),
        arm_controller(make_pick_place_arm_controller(arm, mode)),
        fingers(make_pick_place_fingers(scene, mode, 8.0)) {
    sim.add_controller(*arm_controller);
    sim.add_controller(*fingers);
    std::vector<double> qpos = scene.model.keyframe_qpos("home");
    sim.set_state(qpos, std::vector<double>(static_cast<std::size_t>(scene.model.nv()), 0.0));
    if (grasp == GraspKind::weld) weld.emplace(sim, scene.weld);
    monitor.emplace(sim, scene.hand, scene.object,
                    GeomSet::of_geoms(scene.model, {scene.fingers[0]}),
                    GeomSet::of_geoms(scene.model, {scene.fingers[1]}));
    table_watch = sim.watch_contacts(GeomSet::of_bodies(scene.model, {scene.robot_root}, true),
                                     GeomSet::of_bodies(scene.model, {scene.table}, false));
    goal.X_WS = frame_pose(scene.model.model(), sim.data(), arm.frame());
    goal.object = Eigen::Vector3d(0.25, 0.05, 0.765);
    goal.target = Eigen::Vector3d(0.25, -0.1, 0.765);
    goal.R_grasp = goal.X_WS.R;
    goal.grasp = grasp;
    goal.posture = arm.gather(sim.data().qpos);
  }
  static PickPlaceSceneOptions scene_options(SimulationMode mode) {
    PickPlaceSceneOptions o;
    o.mode = mode;
    o.object.position = {0.25, 0.05};
    o.target = {0.25, -0.1};
    o.noslip_iterations = 10;
    return o;
  }
  static SimulationOptions sim_options(SimulationMode mode) {
    SimulationOptions o;
    o.mode = mode;
    return o;
  }
};

PickPlaceMotion quick() {
  PickPlaceMotion m;
  m.dwell_time = 0.1;
  m.grip_time = 0.3;
  m.release_time = 0.3;
  m.settle_time = 0.3;
  m.limits.max_velocity = 0.3;
  m.limits.max_acceleration = 3.0;
  return m;
}

TEST(PickPlaceTask, ScheduleAndSegments) {
  Rig rig(SimulationMode::position, GraspKind::weld);
  const PickPlaceMotion m;  // the classic constants
  PickPlaceTask task(rig.sim, rig.arm, rig.goal, m, *rig.monitor, &*rig.weld, rig.table_watch);
  const auto& s = task.schedule();
  const auto& seg = task.segments();
  // 14 states: the moves last their trapezoids, the dwells 0.5 s, the finger ramps 0.6 s
  EXPECT_EQ(s[0], 0.0);
  const double expected[14] = {
      seg[0].duration(), 0.5, seg[1].duration(), 0.5, 0.6, 0.5, seg[2].duration(), 0.5,
      seg[3].duration(), 0.5, seg[4].duration(), 0.5, 0.6, 1.0};
  for (int k = 0; k < 14; ++k) EXPECT_NEAR(s[k + 1] - s[k], expected[k], 1e-12) << k;
  // the tool poses: above the object, at the grasp, lifted, above the target, release
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  EXPECT_LT((seg[0].goal().p - (rig.goal.object + 0.055 * up)).norm(), 1e-15);
  EXPECT_LT((seg[1].goal().p - (rig.goal.object + 0.010 * up)).norm(), 1e-15);
  EXPECT_LT((seg[2].goal().p - (rig.goal.object + 0.12 * up)).norm(), 1e-15);
  EXPECT_LT((seg[3].goal().p - (rig.goal.target + 0.12 * up)).norm(), 1e-15);
  EXPECT_LT((seg[4].goal().p - (rig.goal.target + 0.055 * up)).norm(), 1e-15);
  EXPECT_TRUE(seg[0].start().is_approx(rig.goal.X_WS, 0.0));
  // DESCEND: 0.045 m at 0.07 m/s, 0.9 m/s²
  EXPECT_NEAR(seg[1].duration(), 2 * 0.07 / 0.9 + (0.045 - 0.07 * 0.07 / 0.9) / 0.07, 1e-12);
  EXPECT_STREQ(to_string(PickPlaceState::dwell_f), "DWELL_F");
}

TEST(PickPlaceTask, TheWeldIsOnFromDwellCToRelease) {
  Rig rig(SimulationMode::torque, GraspKind::weld);
  PickPlaceTask task(rig.sim, rig.arm, rig.goal, quick(), *rig.monitor, &*rig.weld,
                     rig.table_watch);
  const auto& s = task.schedule();
  bool on_before = false, on_during = true, on_after = false;
  for (;;) {
    const TickResult tick = rig.sim.tick(task);
    if (tick.status == TickStatus::finished) break;
    ASSERT_TRUE(tick.ok());
    const double t = rig.sim.time() - task.trace().start_time;
    const bool on = rig.weld->active();
    if (task.state() < PickPlaceState::dwell_c) on_before = on_before || on;
    if (task.state() >= PickPlaceState::dwell_c && task.state() < PickPlaceState::release)
      on_during = on_during && on;
    if (task.state() >= PickPlaceState::release) on_after = on_after || on;
    ASSERT_LT(t, s.back() + 0.1);
  }
  EXPECT_FALSE(on_before);
  EXPECT_TRUE(on_during);
  EXPECT_FALSE(on_after);
  EXPECT_EQ(task.state(), PickPlaceState::done);
  EXPECT_NEAR(task.trace().done_time, s[13], 1e-9);
  EXPECT_LT(task.trace().weld_jump, 0.05e-3);
}

// the trace's weld jump sees a weld written from a stale pose: the data as compiled (the relative
// pose at qpos0) put back right after the task switched the weld on yanks the object by
// millimetres within the measuring window
TEST(PickPlaceTask, TheWeldJumpSeesAStaleWeld) {
  Rig rig(SimulationMode::position, GraspKind::weld);
  PickPlaceTask task(rig.sim, rig.arm, rig.goal, quick(), *rig.monitor, &*rig.weld,
                     rig.table_watch);
  const int weld = rig.weld->equality();
  const mjModel& file = rig.scene.model.model();
  const std::vector<double> compiled(file.eq_data + mjNEQDATA * weld,
                                     file.eq_data + mjNEQDATA * (weld + 1));
  bool stale = false;
  while (task.state() < PickPlaceState::lift) {
    ASSERT_TRUE(rig.sim.tick(task).ok());
    if (!stale && task.state() == PickPlaceState::dwell_c) {
      ASSERT_TRUE(rig.weld->active());
      ASSERT_TRUE(rig.sim.set_equality_data(weld, compiled));
      stale = true;
    }
  }
  ASSERT_TRUE(stale);
  EXPECT_GT(task.trace().weld_jump, 1e-3);
}

TEST(PickPlaceTask, TheControlLoopAllocatesNothing) {
  for (const SimulationMode mode : {SimulationMode::position, SimulationMode::torque}) {
    SCOPED_TRACE(to_string(mode));
    Rig rig(mode, GraspKind::weld);
    PickPlaceTask task(rig.sim, rig.arm, rig.goal, quick(), *rig.monitor, &*rig.weld,
                       rig.table_watch);
    ASSERT_TRUE(rig.sim.tick(task).ok());  // the first tick sizes the references
    const std::uint64_t before = test::malloc_calls();
    int ticks = 0;
    while (rig.sim.tick(task).ok()) ++ticks;
    EXPECT_EQ(test::malloc_calls() - before, 0u);
    EXPECT_GT(ticks, 1000);  // through every state
    EXPECT_EQ(task.state(), PickPlaceState::done);
  }
}

TEST(PickPlaceTask, BadInput) {
  Rig rig(SimulationMode::position, GraspKind::weld);
  const auto error = [&](PickPlaceGoal goal, PickPlaceMotion motion, WeldGrasp* weld, int watch) {
    return test::error_of(
        [&] { PickPlaceTask(rig.sim, rig.arm, goal, motion, *rig.monitor, weld, watch); });
  };
  PickPlaceGoal goal = rig.goal;
  EXPECT_NE(error(goal, quick(), nullptr, rig.table_watch).find("needs a WeldGrasp"),
            std::string::npos);
  goal.target.x() = NAN;
  EXPECT_NE(error(goal, quick(), &*rig.weld, rig.table_watch).find("finite"), std::string::npos);
  goal = rig.goal;
  goal.posture = Eigen::VectorXd::Zero(3);
  EXPECT_NE(error(goal, quick(), &*rig.weld, rig.table_watch).find("posture"), std::string::npos);
  PickPlaceMotion motion = quick();
  motion.approach_height = 0.005;
  EXPECT_NE(error(rig.goal, motion, &*rig.weld, rig.table_watch).find("approach_height"),
            std::string::npos);
  motion = quick();
  motion.limits.max_velocity = -1.0;
  EXPECT_NE(error(rig.goal, motion, &*rig.weld, rig.table_watch).find("max_velocity"),
            std::string::npos);
  EXPECT_NE(error(rig.goal, quick(), &*rig.weld, 7).find("contact watch 7"), std::string::npos);
}

}  // namespace
}  // namespace mjarm
