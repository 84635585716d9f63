#include "mjarm/control/control_benchmark.hpp"

#include <gtest/gtest.h>

#include <string>

#include "ik/malloc_counter.hpp"
#include "mjarm/control/gravity_compensation.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/error.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

Chain panda_torque() { return Chain(Robot::bundled("panda_torque"), "attachment_site"); }

TEST(ControlBenchmark, TimesEveryControllerWithoutAllocations) {
  const Chain chain = panda_torque();
  ControlBenchmarkOptions o;
  o.steps = 400;
  o.warmup = 20;
  o.allocation_count = [] { return test::malloc_calls(); };
  int last_phase = 0;
  o.progress = [&](int done, int total) {
    EXPECT_EQ(done, last_phase + 1);
    EXPECT_EQ(total, 12);
    last_phase = done;
  };
  const ControlBenchmarkResult r = run_control_benchmark(chain, o);
  EXPECT_EQ(last_phase, 12);
  EXPECT_EQ(r.robot, "panda_torque");
  EXPECT_EQ(r.joints, 7);
  EXPECT_DOUBLE_EQ(r.timestep, 0.002);
  EXPECT_DOUBLE_EQ(r.frequency, 0.5);  // 1000 steps per period
  const std::vector<std::string> names{"joint-pd", "gravity", "ct",  "task-pd", "accel",
                                       "osc",      "se3",     "cic", "hqp-ac",  "observer"};
  ASSERT_EQ(r.controllers.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto& c = r.controllers[i];
    EXPECT_EQ(c.name, names[i]);
    EXPECT_EQ(c.steps, 400);
    EXPECT_EQ(c.allocations, 0) << c.name;
    EXPECT_EQ(c.allocations_per_step, 0.0) << c.name;
    EXPECT_GT(c.median_us, 0.0);
    EXPECT_LE(c.median_us, c.p99_us);
    EXPECT_LE(c.p99_us, c.max_us);
    EXPECT_GT(c.mean_us, 0.0);
    // the tracking controllers follow the reference (its amplitude moves the tool ~0.1 m)
    if (c.name != "gravity") {
      EXPECT_LT(c.rms_position_error, 0.02) << c.name;
    }
  }
  // computed torque, OSC and SE(3) impedance cancel the dynamics: they track tightly
  EXPECT_LT(r.controllers[2].rms_position_error, 1e-3);
  EXPECT_LT(r.controllers[5].rms_position_error, 2e-3);
  EXPECT_LT(r.controllers[6].rms_position_error, 2e-3);  // se3: the same exact cancellation
  EXPECT_LT(r.controllers[7].rms_position_error, 2e-3);  // cic
  EXPECT_LT(r.controllers[8].rms_position_error, 2e-3);  // hqp-ac
  // the observer rides along an OSC loop: the same tracking as OSC's own phase
  EXPECT_NEAR(r.controllers[9].rms_position_error, r.controllers[5].rms_position_error, 1e-9);
  EXPECT_EQ(r.loop_allocations, 0);
  EXPECT_GT(r.osc_real_time_factor, 0.0);
  EXPECT_GT(r.passive_real_time_factor, 0.0);
  EXPECT_GT(r.osc_step_us, 0.0);
  EXPECT_GT(r.passive_step_us, 0.0);
}

TEST(ControlBenchmark, WithoutACounterAllocationsAreNotReported) {
  ControlBenchmarkOptions o;
  o.steps = 20;
  o.warmup = 0;
  const ControlBenchmarkResult r = run_control_benchmark(panda_torque(), o);
  for (const auto& c : r.controllers) {
    EXPECT_EQ(c.allocations, -1);
    EXPECT_EQ(c.allocations_per_step, -1.0);
  }
  EXPECT_EQ(r.loop_allocations, -1);
}

TEST(ControlBenchmark, BadInputThrows) {
  const Chain chain = panda_torque();
  auto with = [&](auto edit) {
    ControlBenchmarkOptions o;
    edit(o);
    return o;
  };
  EXPECT_THROW(run_control_benchmark(chain, with([](auto& o) { o.steps = 0; })), Error);
  EXPECT_THROW(run_control_benchmark(chain, with([](auto& o) { o.warmup = -1; })), Error);
  EXPECT_THROW(run_control_benchmark(chain, with([](auto& o) { o.amplitude = NAN; })), Error);
  EXPECT_THROW(run_control_benchmark(chain, with([](auto& o) { o.frequency = 0.0; })), Error);
  // position servos: the benchmark names the torque variant
  const Chain servo(Robot::bundled("panda"), "attachment_site");
  try {
    run_control_benchmark(servo, with([](auto& o) { o.steps = 1; }));
    ADD_FAILURE() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("_torque"), std::string::npos) << e.what();
  }
  // a position-kind controller cannot be timed on motors
  std::vector<std::unique_ptr<Controller>> controllers;
  controllers.push_back(std::make_unique<GravityCompensationController>(servo));
  EXPECT_THROW(run_control_benchmark(chain, controllers, with([](auto& o) { o.steps = 1; })),
               Error);
}

/// Two motor-driven hinges, on a fixed base, whose links weigh almost nothing: the first
/// command accelerates them beyond MuJoCo's bound, so it flags a bad qacc and resets the state.
constexpr const char* kFeatherArm = R"(
<mujoco model="feather_arm">
  <compiler autolimits="true"/>
  <option timestep="0.002"/>
  <worldbody>
    <body name="link1" pos="0 0 0.5">
      <joint name="j1" type="hinge" axis="0 1 0" range="-2 2"/>
      <inertial pos="0 0 0" mass="1e-9" diaginertia="1e-14 1e-14 1e-14"/>
      <body name="link2" pos="0.4 0 0">
        <joint name="j2" type="hinge" axis="0 1 0" range="-2 2"/>
        <inertial pos="0.2 0 0" mass="1e-9" diaginertia="1e-14 1e-14 1e-14"/>
        <site name="tip" pos="0.35 0 0"/>
      </body>
    </body>
  </worldbody>
  <actuator>
    <motor joint="j1" gear="1"/>
    <motor joint="j2" gear="1"/>
  </actuator>
</mujoco>
)";

TEST(ControlBenchmark, MuJoCoBadStateWarningsFaultTheRun) {
  const Robot robot = Robot::from_string(kFeatherArm);
  const Chain chain(robot, "tip");
  ControlBenchmarkOptions o;
  o.steps = 2000;
  o.warmup = 0;
  const ControlBenchmarkResult r = run_control_benchmark(chain, o);
  EXPECT_EQ(r.status, ControlBenchmarkStatus::faulted);
  EXPECT_NE(r.message.find("bad qacc"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("while running 'joint-pd'"), std::string::npos) << r.message;
  EXPECT_TRUE(r.controllers.empty());  // no figures from a reset simulation
  EXPECT_STREQ(to_string(r.status), "faulted");
  // the bundled torque panda runs clean
  o.steps = 50;
  EXPECT_EQ(run_control_benchmark(panda_torque(), o).status, ControlBenchmarkStatus::ok);
}

/// A damped two-hinge arm whose base hangs from @p base_joint (a free or a ball joint): the
/// controllers drive the hinges only, so the base falls or swings with no MuJoCo warning, and
/// the tracking figures measure that fall (kilometres of "tracking error" for a free base).
std::string arm_on(const std::string& base_joint) {
  return R"(
<mujoco model="arm_on_)" +
         base_joint + R"(">
  <compiler autolimits="true"/>
  <option timestep="0.002"/>
  <worldbody>
    <body name="base" pos="0 0 1">
      )" +
         (base_joint == "free" ? "<freejoint name=\"root\"/>"
                               : "<joint name=\"root\" type=\"ball\"/>") +
         R"(
      <geom type="box" size="0.1 0.1 0.1" mass="5"/>
      <body name="link1" pos="0 0 0.1">
        <joint name="j1" axis="0 0 1" range="-2 2" damping="1"/>
        <geom type="capsule" fromto="0 0 0 0 0 0.3" size="0.03" mass="1"/>
        <body name="link2" pos="0 0 0.3">
          <joint name="j2" axis="0 1 0" range="-2 2" damping="1"/>
          <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03" mass="1"/>
          <site name="tip" pos="0.3 0 0"/>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <motor joint="j1" ctrlrange="-50 50"/>
    <motor joint="j2" ctrlrange="-50 50"/>
  </actuator>
</mujoco>)";
}

// issue 16, item 6: "a warning that means the numbers are meaningless must fail the command" —
// the same meaningless numbers without any warning: an arm whose base is not fixed
TEST(ControlBenchmark, AnArmWhoseBaseIsNotFixedIsRefused) {
  ControlBenchmarkOptions o;
  o.steps = 200;
  o.warmup = 0;
  for (const std::string joint : {"free", "ball"}) {
    const Robot robot = Robot::from_string(arm_on(joint));
    const Chain chain(robot, "tip");
    const std::string message = test::error_of([&] { run_control_benchmark(chain, o); });
    EXPECT_NE(message.find("control benchmark: the frame 'tip' of model 'arm_on_" + joint +
                           "' hangs from " + joint + " joint 'root'"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("fixed base"), std::string::npos) << message;
  }
}

TEST(ControlBenchmark, AStopRequestInterruptsTheRun) {
  ControlBenchmarkOptions o;
  o.steps = 5000;
  o.warmup = 0;
  int asked = 0;
  o.stop = [&] { return ++asked > 2; };
  const ControlBenchmarkResult r = run_control_benchmark(panda_torque(), o);
  EXPECT_EQ(r.status, ControlBenchmarkStatus::interrupted);
  EXPECT_EQ(asked, 3);
  EXPECT_TRUE(r.controllers.empty());
}

}  // namespace
}  // namespace mjarm
