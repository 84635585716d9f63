#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "sim/sim_test_support.hpp"

namespace mjarm {
namespace {

// One hinge (inertia 0.01 kg m², no gravity) under a position servo far too stiff for the
// explicit servo term: h·ω = 0.002·sqrt(2e4 / 0.01) ≈ 2.8 > 2, so every step multiplies the
// error by about −5.8.
constexpr const char* kStiffServo = R"(
<mujoco model="stiff">
  <option timestep="0.002" integrator="Euler" gravity="0 0 0"/>
  <worldbody>
    <body name="link">
      <joint name="hinge" axis="0 0 1"/>
      <inertial pos="0 0 0" mass="1" diaginertia="0.01 0.01 0.01"/>
      <geom type="box" size="0.05 0.01 0.01" contype="0" conaffinity="0"/>
      <site name="tip" pos="0.05 0 0"/>
    </body>
  </worldbody>
  <actuator>
    <general name="servo" joint="hinge" gainprm="2e4" biastype="affine" biasprm="0 -2e4 0"/>
  </actuator>
</mujoco>)";

Reference target(double q) {
  Reference r;
  r.joint.q = Eigen::VectorXd::Constant(1, q);
  return r;
}

TEST(Divergence, RunawayAccelerationStopsWithTimeAndJointAndKeepsTheRows) {
  const Robot robot = Robot::from_string(kStiffServo);
  const Chain chain(robot, "tip");
  SimulationOptions options;
  options.mode = SimulationMode::position;
  Simulation sim(robot, options);
  test::PositionTarget servo(chain);
  sim.add_controller(servo);
  test::TempDir dir("runaway");
  RunResult run;
  {
    Recorder recorder(sim, dir.path());
    ConstantReferenceSource source(target(1e-6));
    run = sim.run(source, 1.0, &recorder);
    recorder.finalize(run);
  }
  ASSERT_EQ(run.status, RunStatus::diverged) << run.message;
  EXPECT_EQ(run.fault.cause, FaultCause::acceleration_bound);
  EXPECT_EQ(run.fault.joint, robot.joint("hinge"));
  EXPECT_GT(run.fault.time, 0.005);  // a few good steps first
  EXPECT_LT(run.fault.time, 0.1);
  EXPECT_NE(run.message.find("joint 'hinge'"), std::string::npos) << run.message;
  EXPECT_NE(run.message.find("t = "), std::string::npos) << run.message;
  // the simulation holds the last good state and stays stopped
  EXPECT_TRUE(std::isfinite(sim.data().qpos[0]));
  EXPECT_EQ(sim.time(), run.fault.time);
  EXPECT_EQ(sim.tick(target(0.0)).status, TickStatus::diverged);
  // every good step was recorded, the divergence is an event, the summary says so
  const test::Csv state = test::read_csv(dir.path() / "state.csv");
  const long good_steps = std::lround(run.fault.time / robot.model().opt.timestep);
  EXPECT_EQ(static_cast<long>(state.rows.size()), good_steps);
  EXPECT_LT(state.value(state.rows.size() - 1, "t"), run.fault.time);
  EXPECT_TRUE(state.ends_with_newline);
  const test::Csv events = test::read_csv(dir.path() / "events.csv");
  ASSERT_EQ(events.rows.size(), 1u);
  EXPECT_EQ(events.rows[0][1], "divergence");
  EXPECT_NE(events.rows[0][2].find("hinge"), std::string::npos);
  const nlohmann::json summary = nlohmann::json::parse(test::read_text(dir.path() / "summary.json"));
  EXPECT_EQ(summary["status"], "diverged");
  EXPECT_EQ(summary["counts"]["state_rows"], good_steps);
  EXPECT_EQ(test::partial_folders(dir.path()), 0);
  // reset clears the fault
  sim.reset();
  EXPECT_TRUE(sim.fault().ok());
  EXPECT_TRUE(sim.tick(target(0.0)).ok());
}

// With no acceleration bound the values grow until MuJoCo itself flags them (and resets its
// data): the fault is still caught, named and the last good state restored.
TEST(Divergence, MujocoBadValueWarningIsCaught) {
  const Robot robot = Robot::from_string(kStiffServo);
  const Chain chain(robot, "tip");
  SimulationOptions options;
  options.mode = SimulationMode::position;
  options.max_acceleration = std::numeric_limits<double>::infinity();
  Simulation sim(robot, options);
  test::PositionTarget servo(chain);
  sim.add_controller(servo);
  ConstantReferenceSource source(target(1e-6));
  const RunResult run = sim.run(source, 5.0);
  ASSERT_EQ(run.status, RunStatus::diverged) << run.message;
  EXPECT_TRUE(run.fault.cause == FaultCause::mujoco_warning ||
              run.fault.cause == FaultCause::nonfinite_qacc ||
              run.fault.cause == FaultCause::nonfinite_qvel)
      << to_string(run.fault.cause);
  EXPECT_EQ(run.fault.joint, robot.joint("hinge"));
  EXPECT_GT(run.fault.time, 0.01);
  EXPECT_NE(run.message.find("'hinge'"), std::string::npos) << run.message;
  EXPECT_EQ(sim.time(), run.fault.time);  // not MuJoCo's reset time 0
  EXPECT_TRUE(std::isfinite(sim.data().qpos[0]));
  EXPECT_GT(std::abs(sim.data().qpos[0]), 1e-3);  // the last good state, not qpos0
}

// The same servo beside a free ball welded to the world, the weld active as compiled: MuJoCo's
// reset on a bad value switches the weld back on and clears the applied forces; the rollback
// puts back the state the step started from, inputs included (the snapshot holds every state
// component the model has).
TEST(Divergence, TheRollbackRestoresTheSwitchesAndTheAppliedForces) {
  std::string xml = kStiffServo;
  xml.replace(xml.find("  </worldbody>"), 0,
              "    <body name=\"ball\" pos=\"1 0 0\"><freejoint/>"
              "<geom size=\"0.05\" contype=\"0\" conaffinity=\"0\"/></body>\n");
  xml.replace(xml.find("  <actuator>"), 0,
              "  <equality><weld name=\"hold\" body1=\"ball\"/></equality>\n");
  const Robot robot = Robot::from_string(xml);
  const Chain chain(robot, "tip");
  SimulationOptions options;
  options.mode = SimulationMode::position;
  options.max_acceleration = std::numeric_limits<double>::infinity();
  Simulation sim(robot, options);
  test::PositionTarget servo(chain);
  sim.add_controller(servo);
  const int hold = sim.equality("hold");
  ASSERT_TRUE(sim.set_equality_active(hold, false));
  const int ball = robot.body("ball");
  sim.data().xfrc_applied[6 * ball + 2] = 0.25;  // a small push up, kept by the user
  ConstantReferenceSource source(target(1e-6));
  const RunResult run = sim.run(source, 5.0);
  ASSERT_EQ(run.status, RunStatus::diverged) << run.message;
  EXPECT_EQ(sim.data().eq_active[hold], 0);                 // not the compiled 1
  EXPECT_EQ(sim.data().xfrc_applied[6 * ball + 2], 0.25);   // not cleared
  EXPECT_EQ(sim.time(), run.fault.time);
}

TEST(Divergence, NanCommandStopsNamingControllerJointAndTime) {
  const Robot robot = Robot::bundled("planar2_torque");
  const Chain chain(robot, "tip");
  Simulation sim(robot);
  sim.reset("home");
  test::FixedTorque broken(chain, Eigen::Vector2d(1.0, 0.5), 0.1, 1);
  sim.add_controller(broken);
  test::TempDir dir("nan");
  RunResult run;
  {
    Recorder recorder(sim, dir.path());
    ConstantReferenceSource source{Reference{}};
    run = sim.run(source, 1.0, &recorder);
    recorder.finalize(run);
  }
  ASSERT_EQ(run.status, RunStatus::bad_command) << run.message;
  EXPECT_GE(run.fault.time, 0.1 - 1e-9);
  EXPECT_LT(run.fault.time, 0.1 + 0.002 + 1e-9);
  EXPECT_NE(run.message.find("controller 'fixed'"), std::string::npos) << run.message;
  EXPECT_NE(run.message.find("joint 'elbow'"), std::string::npos) << run.message;
  // nothing non-finite reached MuJoCo
  for (int a = 0; a < robot.nu(); ++a) EXPECT_TRUE(std::isfinite(sim.data().ctrl[a]));
  const test::Csv task = test::read_csv(dir.path() / "task.csv");
  EXPECT_EQ(static_cast<long>(task.rows.size()), run.ticks);
  const nlohmann::json summary = nlohmann::json::parse(test::read_text(dir.path() / "summary.json"));
  EXPECT_EQ(summary["status"], "bad_command");
}

}  // namespace
}  // namespace mjarm
