// GraspMonitor: the grasp force against MuJoCo's own contact forces, the load of a held object,
// slip and drop events, the creep a soft contact allows without the noslip solver, bad input.

#include "mjarm/sim/grasp_monitor.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ik/malloc_counter.hpp"
#include "mjarm/control/finger_force.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/contacts.hpp"
#include "mjarm/sim/simulation.hpp"
#include "support/error_message.hpp"
#include "support/finger_rig.hpp"

namespace mjarm {
namespace {

struct Grip {
  Robot robot;
  Chain chain{robot, {"left", "right"}, "hand"};
  Simulation sim;
  FingerForceController fingers;
  GraspMonitor monitor;
  Reference reference;

  explicit Grip(bool gravity, int noslip = 10, double force = 6.0)
      : robot(Robot::from_string(test::finger_rig(false, gravity, 400.0, noslip))),
        sim(robot, torque_mode()),
        fingers(chain, options(robot, force)),
        monitor(sim, "hand", "cube", GeomSet::of_geoms(robot, {"left"}),
                GeomSet::of_geoms(robot, {"right"})) {
    std::vector<double> qpos(robot.model().qpos0, robot.model().qpos0 + robot.nq());
    qpos[0] = qpos[1] = 0.04;  // fingers open
    sim.set_state(qpos, std::vector<double>(static_cast<std::size_t>(robot.nv()), 0.0));
    sim.add_controller(fingers);
    reference.gripper = 1.0;
  }
  static SimulationOptions torque_mode() {
    SimulationOptions o;
    o.mode = SimulationMode::torque;
    return o;
  }
  static FingerForceOptions options(const Robot& robot, double force) {
    FingerForceOptions o;
    o.grasp_force = force;
    o.finger_geoms = {{robot.geom("left")}, {robot.geom("right")}};
    o.object_geoms = {robot.geom("cube")};
    return o;
  }
  void run(double seconds) {
    const double end = sim.time() + seconds;
    while (sim.time() < end - 1e-9) {
      ASSERT_TRUE(sim.tick(reference).ok());
      monitor.update();
    }
  }
};

TEST(GraspMonitor, GraspForceIsTheSqueezeMuJoCoComputes) {
  Grip grip(false, 10, 6.0);
  grip.run(1.0);
  const GraspReading& r = grip.monitor.reading();
  EXPECT_GE(r.finger1_contacts, 1);
  EXPECT_GE(r.finger2_contacts, 1);
  EXPECT_NEAR(r.force, 6.0, 0.05);
  // the same from kinematics/contacts: each finger's contact forces on the cube, summed
  const std::vector<ContactForce> all = contact_forces(grip.robot.model(), grip.sim.data());
  Eigen::Vector3d left = Eigen::Vector3d::Zero(), right = Eigen::Vector3d::Zero();
  const int cube = grip.robot.body("cube");
  for (const ContactForce& c : all) {
    const Eigen::Vector3d on_cube = c.body2 == cube ? c.force_W : Eigen::Vector3d(-c.force_W);
    const bool is_left = c.geom1 == grip.robot.geom("left") || c.geom2 == grip.robot.geom("left");
    (is_left ? left : right) += on_cube;
  }
  EXPECT_LT((r.force1_W - left).norm(), 1e-9);
  EXPECT_LT((r.force2_W - right).norm(), 1e-9);
  EXPECT_NEAR(r.force1_W.y(), -6.0, 0.05);  // the left finger pushes towards −y
  EXPECT_LT(r.load_W.norm(), 0.01);         // no gravity: the squeezes cancel
}

TEST(GraspMonitor, LoadIsTheWeightOfAHeldObject) {
  Grip grip(true, 10, 6.0);
  grip.run(1.0);
  const GraspReading& r = grip.monitor.reading();
  const double weight = 0.05 * 9.81;
  EXPECT_NEAR(r.load_W.z(), weight, 0.01 * weight);
  EXPECT_NEAR(r.force, 6.0, 0.05);  // the shared load cancels in ½‖f₁ − f₂‖
  // both fingers carry part of it (how much each is statically indeterminate)
  EXPECT_GT(r.force1_W.z(), 0.1 * weight);
  EXPECT_GT(r.force2_W.z(), 0.1 * weight);
}

TEST(GraspMonitor, SoftContactsCreepWithoutTheNoslipSolver) {
  // MuJoCo's friction is a soft constraint: under a steady load the object slides slowly however
  // hard it is squeezed; the noslip solver removes that creep
  const auto creep = [](int noslip) {
    Grip grip(true, noslip, 6.0);
    grip.run(0.5);
    grip.monitor.close();
    grip.run(2.0);
    return grip.monitor.reading();
  };
  const GraspReading soft = creep(0);
  const GraspReading exact = creep(10);
  EXPECT_GT(soft.slip_speed, 5e-4);  // [m/s]
  EXPECT_GT(soft.slip, 1e-3);
  EXPECT_LT(exact.slip_speed, 1e-5);
  EXPECT_LT(exact.slip, 1e-4);
  RecordProperty("creep_mm_per_s", std::to_string(soft.slip_speed * 1e3));
}

TEST(GraspMonitor, SlipAndDropEventsComeOnceEach) {
  Grip grip(false);
  grip.run(0.5);
  EXPECT_EQ(grip.monitor.update(), GraspEvent::none);
  EXPECT_EQ(grip.monitor.reading().slip, 0.0);  // not closed yet
  grip.monitor.close();
  EXPECT_TRUE(grip.monitor.reading().closed);
  mjData& d = grip.sim.data();
  const int z = grip.robot.joint_info(grip.robot.joint("cube")).qpos_address + 2;
  const auto shift = [&](double dz) {
    d.qpos[z] += dz;
    mj_kinematics(&grip.robot.model(), &d);
    mj_comPos(&grip.robot.model(), &d);
    mj_comVel(&grip.robot.model(), &d);
  };
  shift(-0.001);
  EXPECT_EQ(grip.monitor.update(), GraspEvent::none);
  EXPECT_NEAR(grip.monitor.reading().slip, 0.001, 1e-5);
  shift(-0.0015);
  EXPECT_EQ(grip.monitor.update(), GraspEvent::slipped);
  EXPECT_EQ(grip.monitor.update(), GraspEvent::none);  // once
  EXPECT_TRUE(grip.monitor.reading().slipped);
  shift(-0.02);
  EXPECT_EQ(grip.monitor.update(), GraspEvent::dropped);
  EXPECT_EQ(grip.monitor.update(), GraspEvent::none);
  EXPECT_TRUE(grip.monitor.reading().dropped);
  // the object's speed relative to the gripper
  d.qvel[grip.robot.joint_info(grip.robot.joint("cube")).dof_address] = 0.03;
  mj_comVel(&grip.robot.model(), &d);
  grip.monitor.update();
  EXPECT_NEAR(grip.monitor.reading().slip_speed, 0.03, 1e-9);
  grip.monitor.open();
  EXPECT_EQ(grip.monitor.update(), GraspEvent::none);
  EXPECT_EQ(grip.monitor.reading().slip, 0.0);
}

TEST(GraspMonitor, UpdateAllocatesNothing) {
  Grip grip(true);
  grip.run(0.2);
  grip.monitor.close();
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 50; ++k) (void)grip.monitor.update();
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

TEST(GraspMonitor, BadInput) {
  Grip grip(false);
  Simulation& sim = grip.sim;
  const GeomSet left = GeomSet::of_geoms(grip.robot, {"left"});
  const GeomSet right = GeomSet::of_geoms(grip.robot, {"right"});
  EXPECT_NE(test::error_of([&] { GraspMonitor(sim, "hnd", "cube", left, right); }).find("hand"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] { GraspMonitor(sim, "hand", "cub", left, right); }).find("cube"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] {
              GraspMonitor(sim, "hand", "cube", GeomSet(), right);
            }).find("finger 1 has no geoms"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] {
              GraspMonitor(sim, "hand", "cube", left, right, {0.01, 0.005});
            }).find("drop_distance"),
            std::string::npos);
  EXPECT_NE(
      test::error_of([&] { GraspMonitor(sim, "hand", "hand", left, right); }).find("has no geoms"),
      std::string::npos);
}

}  // namespace
}  // namespace mjarm
