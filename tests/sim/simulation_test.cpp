#include "mjarm/sim/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "ik/malloc_counter.hpp"
#include "mjarm/control/gravity_compensation.hpp"
#include "mjarm/error.hpp"
#include "mjarm/sim/recorder.hpp"
#include "sim/sim_test_support.hpp"

namespace mjarm {
namespace {

using test::FixedTorque;
using test::PdTorque;
using test::PositionTarget;
using test::Spy;

Reference joint_reference(const Eigen::VectorXd& q) {
  Reference r;
  r.joint.q = q;
  r.joint.qd = Eigen::VectorXd::Zero(q.size());
  r.joint.qdd = Eigen::VectorXd::Zero(q.size());
  return r;
}

// planar2_torque with another integrator, loaded from the bundled file's text
Robot planar2_torque_with(const std::string& integrator) {
  std::string xml = test::read_text(Robot::models_dir() / "planar2_torque.xml");
  const std::string from = "integrator=\"Euler\"";
  xml.replace(xml.find(from), from.size(), "integrator=\"" + integrator + "\"");
  return Robot::from_string(xml, Robot::models_dir());
}

TEST(Simulation, ControlPeriodMustBeAWholeMultipleOfTheTimestep) {
  const Robot robot = Robot::bundled("planar2_torque");  // timestep 0.002 s
  SimulationOptions options;
  options.control_period = 0.01;
  EXPECT_EQ(Simulation(robot, options).steps_per_tick(), 5);
  options.control_period = 0.0;
  EXPECT_EQ(Simulation(robot, options).steps_per_tick(), 1);
  for (double bad : {0.005, 0.001, -0.01, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    options.control_period = bad;
    EXPECT_THROW(Simulation(robot, options), Error) << bad;
  }
  options.control_period = 0.005;
  try {
    Simulation sim(robot, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("whole multiple"), std::string::npos) << e.what();
  }
}

TEST(Simulation, RejectsZeroNegativeAndNanTimesteps) {
  auto xml = [](const char* timestep) {
    return std::string("<mujoco><option timestep=\"") + timestep +
           "\"/><worldbody><body><joint name=\"j\"/><geom size=\"0.1\"/></body>"
           "</worldbody></mujoco>";
  };
  for (const char* timestep : {"0", "-0.001"}) {
    const Robot robot = Robot::from_string(xml(timestep));
    try {
      Simulation sim(robot);
      FAIL() << "timestep " << timestep << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("timestep"), std::string::npos) << e.what();
    }
  }
  // a NaN timestep never reaches a simulation: the model is refused at load, naming it
  try {
    (void)Robot::from_string(xml("nan"));
    FAIL() << "timestep nan accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("timestep = nan"), std::string::npos) << e.what();
  }
}

TEST(Simulation, ControllersMustFitTheActuators) {
  const Robot servos = Robot::bundled("panda");
  const Robot motors = Robot::bundled("panda_torque");
  const Chain servo_chain(servos, "attachment_site");
  const Chain motor_chain(motors, "attachment_site");
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // a torque controller on position servos: the joint and what drives it are named
  {
    SimulationOptions options;
    options.mode = SimulationMode::torque;
    Simulation sim(servos, options);
    PdTorque pd(servo_chain, 100, 10);
    const std::string m = message([&] { sim.add_controller(pd); });
    EXPECT_NE(m.find("joint 'joint1'"), std::string::npos) << m;
    EXPECT_NE(m.find("kind position"), std::string::npos) << m;
    EXPECT_NE(m.find("_torque"), std::string::npos) << m;
  }
  // a position controller on motors
  {
    SimulationOptions options;
    options.mode = SimulationMode::position;
    Simulation sim(motors, options);
    PositionTarget target(motor_chain);
    const std::string m = message([&] { sim.add_controller(target); });
    EXPECT_NE(m.find("kind motor"), std::string::npos) << m;
  }
  // the mode decides the kind of command
  {
    SimulationOptions options;
    options.mode = SimulationMode::torque;
    Simulation sim(motors, options);
    PositionTarget target(motor_chain);
    const std::string m = message([&] { sim.add_controller(target); });
    EXPECT_NE(m.find("torque mode takes torque commands"), std::string::npos) << m;
  }
  // kinematic mode takes no controller; a chain of another model is refused; no joint twice
  {
    SimulationOptions options;
    options.mode = SimulationMode::kinematic;
    Simulation sim(motors, options);
    PdTorque pd(motor_chain, 1, 1);
    EXPECT_THROW(sim.add_controller(pd), Error);
  }
  {
    Simulation sim(motors);
    PdTorque other_model(Chain(Robot::bundled("panda_torque"), "attachment_site"), 1, 1);
    EXPECT_NE(message([&] { sim.add_controller(other_model); }).find("share the Robot"), std::string::npos);
    PdTorque first(motor_chain, 1, 1);
    FixedTorque second(Chain(motors, {"joint7"}, "attachment_site"), Eigen::VectorXd::Zero(1));
    sim.add_controller(first);
    const std::string m = message([&] { sim.add_controller(second); });
    EXPECT_NE(m.find("'joint7' is already commanded by controller 'test-pd'"), std::string::npos) << m;
  }
  // no actuator at all
  {
    const Robot bare = Robot::from_string(
        "<mujoco><worldbody><body><joint name=\"free_spin\"/><geom size=\"0.1\"/>"
        "<site name=\"s\"/></body></worldbody></mujoco>");
    Simulation sim(bare);
    PdTorque pd(Chain(bare, "s"), 1, 1);
    const std::string m = message([&] { sim.add_controller(pd); });
    EXPECT_NE(m.find("'free_spin'"), std::string::npos) << m;
    EXPECT_NE(m.find("no actuator"), std::string::npos) << m;
  }
}

// The controller is shown exactly the state of the step it acts on, with fresh dynamics, and
// the split step integrates exactly as mj_step does.
TEST(Simulation, SplitStepShowsTheControllerTheStateOfTheStep) {
  const Robot robot = Robot::bundled("planar2_torque");
  const mjModel& m = robot.model();
  SimulationOptions options;
  options.control_period = 0.006;  // 3 physics steps
  Simulation sim(robot, options);
  sim.reset("home");
  const Chain chain(robot, "tip");
  const int ticks = 100;
  Spy spy(chain, ticks);
  sim.add_controller(spy);
  for (int k = 0; k < ticks; ++k) ASSERT_TRUE(sim.tick(Reference{}).ok());

  // the same law, computed on a plain mj_step loop
  DataPtr plain = robot.make_data();
  DataPtr scratch = robot.make_data();
  mj_resetDataKeyframe(&m, plain.get(), robot.keyframe("home"));
  for (int k = 0; k < ticks; ++k) {
    ASSERT_EQ(spy.time[k], plain->time) << k;
    for (int i = 0; i < m.nq; ++i) ASSERT_EQ(spy.qpos[k * m.nq + i], plain->qpos[i]) << k;
    for (int i = 0; i < m.nv; ++i) ASSERT_EQ(spy.qvel[k * m.nv + i], plain->qvel[i]) << k;
    // fresh dynamics: the bias forces of exactly this state
    mj_copyData(scratch.get(), &m, plain.get());
    mj_forward(&m, scratch.get());
    for (int i = 0; i < m.nv; ++i) ASSERT_NEAR(spy.bias[k * m.nv + i], scratch->qfrc_bias[i], 1e-12) << k;
    for (int i = 0; i < chain.size(); ++i) plain->ctrl[i] = spy.torque(*scratch, i);
    for (int s = 0; s < 3; ++s) mj_step(&m, plain.get());
  }
  for (int i = 0; i < m.nq; ++i) EXPECT_EQ(sim.data().qpos[i], plain->qpos[i]);
  EXPECT_EQ(sim.ticks(), ticks);
  EXPECT_EQ(sim.physics_steps(), 3 * ticks);
  EXPECT_NEAR(sim.time(), 0.6, 1e-12);
}

// RK4: mj_forward gives the controller the state, then mj_step holds ctrl over the stages.
TEST(Simulation, Rk4ShowsTheControllerTheStateAndMatchesForwardPlusStep) {
  const Robot robot = planar2_torque_with("RK4");
  const mjModel& m = robot.model();
  ASSERT_EQ(m.opt.integrator, mjINT_RK4);
  SimulationOptions options;
  options.control_period = 0.004;
  Simulation sim(robot, options);
  ASSERT_TRUE(sim.uses_rk4());
  sim.reset("home");
  const Chain chain(robot, "tip");
  const int ticks = 100;
  Spy spy(chain, ticks);
  sim.add_controller(spy);
  for (int k = 0; k < ticks; ++k) ASSERT_TRUE(sim.tick(Reference{}).ok());

  DataPtr plain = robot.make_data();
  mj_resetDataKeyframe(&m, plain.get(), robot.keyframe("home"));
  for (int k = 0; k < ticks; ++k) {
    mj_forward(&m, plain.get());
    ASSERT_EQ(spy.time[k], plain->time) << k;
    for (int i = 0; i < m.nq; ++i) ASSERT_EQ(spy.qpos[k * m.nq + i], plain->qpos[i]) << k;
    for (int i = 0; i < m.nv; ++i) ASSERT_EQ(spy.bias[k * m.nv + i], plain->qfrc_bias[i]) << k;
    for (int i = 0; i < chain.size(); ++i) plain->ctrl[i] = spy.torque(*plain, i);
    for (int s = 0; s < 2; ++s) mj_step(&m, plain.get());
  }
  for (int i = 0; i < m.nq; ++i) EXPECT_EQ(sim.data().qpos[i], plain->qpos[i]);
}

TEST(Simulation, TorqueIsClippedAndSaturationReported) {
  const Robot robot = Robot::bundled("planar2_torque");  // limits 20 and 10 N·m
  Simulation sim(robot);
  sim.reset("home");
  const Chain chain(robot, "tip");
  FixedTorque fixed(chain, Eigen::Vector2d(50.0, -3.0));
  sim.add_controller(fixed);
  const TickResult r = sim.tick(Reference{});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.saturated, 1);
  EXPECT_EQ(sim.data().ctrl[0], 20.0);
  EXPECT_EQ(sim.data().ctrl[1], -3.0);
  EXPECT_EQ(sim.data().actuator_force[0], 20.0);
  EXPECT_EQ(sim.saturated()[0], 1);
  EXPECT_EQ(sim.saturated()[1], 0);
  sim.tick(Reference{});
  EXPECT_EQ(sim.saturation_counts()[0], 2);
  EXPECT_EQ(sim.saturation_counts()[1], 0);
}

// ctrl = τ ÷ (gear·gain): the joint receives exactly τ; the force limit bounds it too
TEST(Simulation, TorqueIsDividedByGearAndGain) {
  const Robot robot = Robot::from_string(R"(
<mujoco>
  <option gravity="0 0 0"/>
  <worldbody><body><joint name="j" damping="1"/><geom size="0.1" mass="1"/><site name="s"/></body></worldbody>
  <actuator>
    <general name="m" joint="j" gear="2" gainprm="3" ctrllimited="true" ctrlrange="-10 10"
             forcelimited="true" forcerange="-12 12"/>
  </actuator>
</mujoco>)");
  ASSERT_EQ(robot.actuators()[0].kind, ActuatorKind::motor);
  Simulation sim(robot);
  FixedTorque fixed(Chain(robot, "s"), Eigen::VectorXd::Constant(1, 5.0));
  sim.add_controller(fixed);
  sim.tick(Reference{});
  EXPECT_NEAR(sim.data().ctrl[0], 5.0 / 6.0, 1e-15);
  EXPECT_NEAR(sim.data().qfrc_actuator[0], 5.0, 1e-12);
  EXPECT_EQ(sim.saturated()[0], 0);
  // 30 N·m would need force 15 > 12: clipped to force 12, i.e. 24 N·m at the joint
  Simulation sim2(robot);
  FixedTorque strong(Chain(robot, "s"), Eigen::VectorXd::Constant(1, 30.0));
  sim2.add_controller(strong);
  sim2.tick(Reference{});
  EXPECT_NEAR(sim2.data().qfrc_actuator[0], 24.0, 1e-12);
  EXPECT_EQ(sim2.saturated()[0], 1);
}

// Position servos sag under gravity; the compensation removes the sag (planar2 and panda).
TEST(Simulation, PositionModeGravityCompensationRemovesTheSag) {
  for (const char* name : {"planar2", "panda", "planar2 RK4"}) {
    const bool rk4 = name == std::string("planar2 RK4");
    Robot robot = Robot::bundled(rk4 ? "planar2" : name);
    if (rk4) {
      std::string xml = test::read_text(Robot::models_dir() / "planar2.xml");
      xml.replace(xml.find("integrator=\"Euler\""), 18, "integrator=\"RK4\"");
      robot = Robot::from_string(xml, Robot::models_dir());
      ASSERT_EQ(robot.model().opt.integrator, mjINT_RK4);
    }
    const Chain chain(robot, name == std::string("panda") ? "attachment_site" : "tip");
    const std::vector<double> home = robot.keyframe_qpos("home");
    const Eigen::VectorXd q_home = chain.gather(home.data());
    double sag[2];
    for (int compensate = 0; compensate < 2; ++compensate) {
      SimulationOptions options;
      options.mode = SimulationMode::position;
      options.control_period = 0.01;
      options.gravity_compensation = compensate == 1;
      Simulation sim(robot, options);
      sim.reset("home");
      PositionTarget target(chain);
      sim.add_controller(target);
      ConstantReferenceSource source(joint_reference(q_home));
      const RunResult run = sim.run(source, 3.0);
      ASSERT_EQ(run.status, RunStatus::duration_reached) << run.message;
      EXPECT_EQ(run.ticks, 300);
      sag[compensate] = (chain.gather(sim.data().qpos) - q_home).cwiseAbs().maxCoeff();
    }
    EXPECT_GT(sag[0], 1e-3) << name;  // the servo alone sags
    EXPECT_LT(sag[1], 1e-6) << name;  // with the bias forces added it holds home
  }
}

// control/'s servo-target compensation does the same job through the servo: with the
// simulation's own compensation off, the panda holds home just as well.
TEST(Simulation, PositionModeWithTheServoTargetCompensationController) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  SimulationOptions options;
  options.mode = SimulationMode::position;
  options.control_period = 0.01;
  options.gravity_compensation = false;  // the controller compensates: not twice
  Simulation sim(robot, options);
  sim.reset("home");
  GravityCompensationController hold(chain);
  sim.add_controller(hold);
  const std::vector<double> home = robot.keyframe_qpos("home");
  const Eigen::VectorXd q_home = chain.gather(home.data());
  ConstantReferenceSource source(joint_reference(q_home));
  ASSERT_TRUE(sim.run(source, 3.0).ok());
  EXPECT_LT((chain.gather(sim.data().qpos) - q_home).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(Simulation, TorqueModeTracksOnPanda) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  SimulationOptions options;
  options.control_period = 0.002;
  Simulation sim(robot, options);
  sim.reset("home");
  PdTorque pd(chain, 400.0, 40.0);
  sim.add_controller(pd);
  const std::vector<double> home = robot.keyframe_qpos("home");
  const Eigen::VectorXd goal = chain.gather(home.data()) + Eigen::VectorXd::Constant(7, 0.1);
  ConstantReferenceSource source(joint_reference(goal));
  const RunResult run = sim.run(source, 2.0);
  ASSERT_TRUE(run.ok()) << run.message;
  EXPECT_LT((chain.gather(sim.data().qpos) - goal).cwiseAbs().maxCoeff(), 1e-3);
}

// Arm and gripper: two commands in one tick, each onto its own actuators.
TEST(Simulation, SeveralControllersPerTick) {
  const Robot robot = Robot::bundled("panda_hand_torque");
  const Chain arm(robot, "attachment_site");
  const Chain fingers(robot, {"finger_left", "finger_right"}, "tcp");
  Simulation sim(robot);
  sim.reset("home");
  PdTorque pd(arm, 100.0, 10.0);
  FixedTorque squeeze(fingers, Eigen::Vector2d(-5.0, -6.0));
  sim.add_controller(pd);
  sim.add_controller(squeeze);
  const std::vector<double> home = robot.keyframe_qpos("home");
  ASSERT_TRUE(sim.tick(joint_reference(arm.gather(home.data()))).ok());
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(sim.data().ctrl[*fingers.actuator(i)], sim.command(1).value[i]);
  }
  EXPECT_EQ(sim.data().ctrl[*fingers.actuator(0)], -5.0);
  for (int i = 0; i < arm.size(); ++i) EXPECT_EQ(sim.data().ctrl[*arm.actuator(i)], sim.command(0).value[i]);
}

TEST(Simulation, KinematicModeMovesAndRollsBackContacts) {
  const Robot robot = Robot::bundled("arm6");
  const Chain chain(robot, "grip");
  SimulationOptions options;
  options.mode = SimulationMode::kinematic;
  options.contact_check_a = GeomSet::of_bodies(robot, {"link1"});  // the moving arm
  options.contact_check_b = GeomSet::of_bodies(robot, {"table"}, false);
  Simulation sim(robot, options);
  sim.reset("home");
  EXPECT_THROW(sim.tick(Reference{}), Error);
  Eigen::VectorXd q = chain.gather(sim.data().qpos);
  // lean forward until the hand reaches the table top
  const double dt = 0.01;
  int moves = 0;
  KinematicStep step;
  for (; moves < 400; ++moves) {
    const Eigen::VectorXd before = chain.gather(sim.data().qpos);
    const double t_before = sim.time();
    q[1] += 0.005;
    step = sim.move(chain, q, dt);
    if (step.rolled_back) {
      EXPECT_EQ(chain.gather(sim.data().qpos), before);
      EXPECT_EQ(sim.time(), t_before);
      break;
    }
    EXPECT_NEAR(sim.time(), t_before + dt, 1e-12);
    EXPECT_NEAR(sim.data().qvel[chain.dof_address(1)], 0.005 / dt, 1e-9);
  }
  ASSERT_TRUE(step.rolled_back) << "the arm never reached the table";
  EXPECT_GT(moves, 10);
  EXPECT_EQ(robot.model().geom_bodyid[step.geom_b], robot.body("table"));
  EXPECT_TRUE(options.contact_check_a.contains(step.geom_a));
  // kinematics are fresh after a move: mj_kinematics on a copy agrees
  DataPtr check = robot.make_data();
  std::copy(sim.data().qpos, sim.data().qpos + robot.nq(), check->qpos);
  mj_kinematics(&robot.model(), check.get());
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(sim.data().site_xpos[3 * robot.site("grip") + k], check->site_xpos[3 * robot.site("grip") + k]);
  }
  EXPECT_THROW(sim.move(chain, q, 0.0), Error);
  EXPECT_THROW(sim.move(chain, Eigen::VectorXd::Constant(chain.size(), std::nan("")), dt), Error);
  Simulation dynamic(robot);
  EXPECT_THROW(dynamic.move(chain, q, dt), Error);
}

TEST(Simulation, SensorsByName) {
  const Robot robot = Robot::from_string(R"(
<mujoco>
  <worldbody>
    <body name="link" pos="0 0 1">
      <joint name="hinge" axis="0 1 0" damping="0.1"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02" mass="1"/>
      <site name="tip" pos="0.3 0 0"/>
    </body>
  </worldbody>
  <actuator><motor name="m" joint="hinge"/></actuator>
  <sensor>
    <jointpos name="angle" joint="hinge"/>
    <jointvel name="rate" joint="hinge"/>
    <framepos name="tip_pos" objtype="site" objname="tip"/>
  </sensor>
</mujoco>)");
  Simulation sim(robot);
  const Chain chain(robot, "tip");
  FixedTorque none(chain, Eigen::VectorXd::Zero(1));
  sim.add_controller(none);
  for (int k = 0; k < 50; ++k) sim.tick(Reference{});
  sim.forward();  // sensors of the current state
  EXPECT_EQ(sim.sensor("angle").size(), 1u);
  EXPECT_NEAR(sim.sensor("angle")[0], sim.data().qpos[0], 1e-15);
  EXPECT_NEAR(sim.sensor("rate")[0], sim.data().qvel[0], 1e-15);
  ASSERT_EQ(sim.sensor("tip_pos").size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sim.sensor("tip_pos")[k], sim.data().site_xpos[k], 1e-15);
  EXPECT_LT(sim.sensor("tip_pos")[2], 1.0);  // the link fell
  EXPECT_EQ(sim.sensor(robot.sensor("rate")).data(), sim.sensor("rate").data());
  EXPECT_THROW(sim.sensor("angel"), Error);
  EXPECT_THROW(sim.sensor(7), Error);
}

// With own_model the simulation steps a private copy that its owner may edit: the edit changes
// this simulation's physics and nothing else (the robot's model, another simulation of it).
TEST(Simulation, OwnModelIsAnEditableCopy) {
  const Robot robot = Robot::bundled("planar2_torque");
  const Chain chain(robot, "tip");
  SimulationOptions own_options;
  own_options.own_model = true;
  Simulation own(robot, own_options), shared(robot), reference(robot);
  ASSERT_NE(own.editable_model(), nullptr);
  EXPECT_TRUE(own.owns_model());
  EXPECT_EQ(shared.editable_model(), nullptr);
  EXPECT_NE(&own.model(), &robot.model());
  EXPECT_EQ(&shared.model(), &robot.model());
  const double damping = robot.model().dof_damping[0];
  own.editable_model()->dof_damping[0] = damping + 5.0;
  EXPECT_EQ(robot.model().dof_damping[0], damping);
  FixedTorque a(chain, Eigen::VectorXd::Constant(2, 3.0)),
      b(chain, Eigen::VectorXd::Constant(2, 3.0)), c(chain, Eigen::VectorXd::Constant(2, 3.0));
  own.add_controller(a);
  shared.add_controller(b);
  reference.add_controller(c);
  for (int k = 0; k < 100; ++k) {
    own.tick(Reference{});
    shared.tick(Reference{});
    reference.tick(Reference{});
  }
  EXPECT_EQ(shared.data().qpos[0], reference.data().qpos[0]);
  EXPECT_LT(std::abs(own.data().qvel[0]), std::abs(shared.data().qvel[0]));  // more damping
}

// whole_multiple: the check behind every control period, with the nearest multiple named
TEST(Simulation, WholeMultipleNamesThePeriodAndTheNearestMultiple) {
  EXPECT_EQ(whole_multiple(0.02, 0.002, "x", "the timestep"), 10);
  EXPECT_EQ(whole_multiple(0.002, 0.002, "x", "the timestep"), 1);
  try {
    whole_multiple(0.015, 0.002, "env: control_period", "the step");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(
        m.find("env: control_period 0.015 s is not a whole multiple of the step 0.002 s"),
        std::string::npos)
        << m;
    EXPECT_NE(m.find("nearest: 0.016 s"), std::string::npos) << m;
  }
  EXPECT_THROW(whole_multiple(0.0, 0.002, "x", "y"), Error);
  EXPECT_THROW(whole_multiple(std::numeric_limits<double>::quiet_NaN(), 0.002, "x", "y"), Error);
  EXPECT_THROW(whole_multiple(0.001, 0.002, "x", "y"), Error);
}

// A control tick (split step, controllers, actuators, divergence checks, recorder rows) allocates
// nothing once running.
TEST(Simulation, TickAllocatesNothing) {
  const Robot robot = Robot::bundled("panda_torque");
  const Chain chain(robot, "attachment_site");
  SimulationOptions options;
  options.control_period = 0.006;
  Simulation sim(robot, options);
  sim.reset("home");
  PdTorque pd(chain, 100.0, 10.0);
  sim.add_controller(pd);
  test::TempDir dir("alloc");
  Recorder recorder(sim, dir.path());
  const std::vector<double> home = robot.keyframe_qpos("home");
  ConstantReferenceSource source(joint_reference(chain.gather(home.data())));
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(sim.tick(source, &recorder).ok());
  const std::uint64_t before = test::malloc_calls();
  for (int k = 0; k < 200; ++k) sim.tick(source, &recorder);
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  recorder.finalize("ok");
  EXPECT_EQ(recorder.state_rows(), 205 * 3);
}

}  // namespace
}  // namespace mjarm
