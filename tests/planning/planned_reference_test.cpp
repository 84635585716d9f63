#include "mjarm/planning/planned_reference.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "ik/malloc_counter.hpp"
#include "mjarm/control/gravity_compensation.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/planning/waypoint_planner.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/tasks/shelf_pick/controllers.hpp"
#include "planning/planning_support.hpp"

namespace mjarm {
namespace {

using planning_test::five_waypoints;
using planning_test::home_q;

/// The 5-waypoint plan on @p robot (planned once per robot and test).
JointSpline plan_five(const Chain& chain) {
  const PlanResult r = WaypointPlanner(chain).plan(home_q(chain.robot()), five_waypoints());
  if (!r.ok()) throw Error("test plan failed: " + r.message);
  return r.trajectory;
}

TEST(PlannedReference, TaskReferenceIsTheDerivativeOfTheJointReference) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  PlannedReference source(chain, plan_five(chain));
  Reference b, r;
  const double h = 1e-5;
  // the pose and the twist as functions of time, for the public finite-difference helpers
  const auto pose = [&](const Eigen::VectorXd& t) {
    source.evaluate(t[0], r);
    return r.task.X_WE;
  };
  const auto twist = [&](double t) {
    source.evaluate(t, r);
    return Vector6d(r.task.V_WE);
  };
  for (double t : {0.3, 0.9, 1.7, source.spline()->knot_time(2)}) {
    source.evaluate(t, b);
    // velocity: central difference of the pose, [ṗ; ω] in world axes
    const Vector6d V = finite_difference_pose_jacobian(pose, Eigen::VectorXd::Constant(1, t),
                                                       JacobianFrame::world_aligned, h)
                           .col(0);
    EXPECT_LT((V.head<3>() - b.task.V_WE.head<3>()).norm(), 1e-6) << t;
    EXPECT_LT((V.tail<3>() - b.task.V_WE.tail<3>()).norm(), 1e-6) << t;
    // acceleration: central difference of the twist (J q̈ + J̇ q̇)
    const Vector6d A = finite_difference_derivative(twist, t, h);
    EXPECT_LT((A - b.task.A_WE).norm(), 1e-4) << t;
  }
}

TEST(PlannedReference, KinematicModeFollowsItExactly) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  PlannedReference source(chain, plan_five(chain), 0.0);
  SimulationOptions options;
  options.mode = SimulationMode::kinematic;
  Simulation sim(robot, options);
  Reference reference;
  const double dt = 0.01;
  for (double t = 0.0; t <= source.run_time(); t += dt) {
    source.evaluate(t, reference);
    sim.move(chain, reference.joint.q, dt);
    source.update(sim.data(), reference);  // measures the tracking of the moved state
  }
  EXPECT_GT(source.tracking().ticks, 100);
  // update reads the moved state at data.time − t₀ = t: the same q as the reference
  EXPECT_LT(source.tracking().max_position, 1e-12);
}

TEST(PlannedReference, TorqueControllersTrackTheWaypointPath) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  const JointSpline plan = plan_five(chain);
  for (const char* name : {"ct", "osc"}) {
    Simulation sim(robot);
    const std::unique_ptr<Controller> controller =
        make_shelf_pick_controller(name, chain, shelf_pick_robot("panda"));
    sim.add_controller(*controller);
    sim.reset("home");
    PlannedReference source(chain, plan, 0.5, 0.5 * sim.timestep());
    const RunResult run = sim.run(source, source.run_time() + 1.0);
    EXPECT_EQ(run.status, RunStatus::finished) << name << ": " << run.message;
    EXPECT_LT(source.tracking().max_position, 0.01) << name;
    EXPECT_LT(source.tracking().final_position, 0.002) << name;
    EXPECT_LE(source.tracking().rms_position, source.tracking().max_position);
  }
}

TEST(PlannedReference, PositionServosTrackItToo) {
  const Robot robot = Robot::bundled("panda");  // position servos
  const Chain chain(robot, "attachment_site");
  SimulationOptions options;
  options.mode = SimulationMode::position;
  options.gravity_compensation = false;
  Simulation sim(robot, options);
  GravityCompensationController controller(chain);
  sim.add_controller(controller);
  sim.reset("home");
  PlannedReference source(chain, plan_five(chain), 0.5, 0.5 * sim.timestep());
  const RunResult run = sim.run(source, source.run_time() + 1.0);
  EXPECT_EQ(run.status, RunStatus::finished) << run.message;
  EXPECT_LT(source.tracking().max_position, 0.05);
  EXPECT_LT(source.tracking().final_position, 0.005);
}

TEST(PlannedReference, TicksAllocateNothingAfterTheFirst) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  PlannedReference source(chain, plan_five(chain), 0.5, 0.001);
  DataPtr data = robot.make_data();
  Reference reference;
  source.update(*data, reference);  // sizes the reference
  const std::uint64_t before = test::malloc_calls();
  bool running = true;
  for (int j = 1; j <= 250; ++j) {
    data->time = 0.02 * j;
    running = source.update(*data, reference) && running;
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  EXPECT_FALSE(running);  // 5 s > duration + hold (4.41 s)
  EXPECT_EQ(source.tracking().ticks, 251);
}

TEST(PlannedReference, BadInputIsAnError) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  EXPECT_THROW(PlannedReference(chain, JointSpline()), Error);
  EXPECT_THROW(PlannedReference(chain, plan_five(chain), -1.0), Error);
  const JointSpline two({Eigen::VectorXd::Zero(2), Eigen::VectorXd::Ones(2)},
                        {Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2)}, {1.0});
  EXPECT_THROW(PlannedReference(chain, two), Error);
}

}  // namespace
}  // namespace mjarm
