// The viewer's simulation without a window: every mode reaches a target set on the panel, mode
// switches carry the state over, the gripper follows its slider, and a step allocates nothing.
#include "mjarm/teleop/viewer_session.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <vector>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/address_sanitizer.hpp"

// ---- allocation counter (see tests/ik/malloc_counter.hpp) ----
// Weak definitions: if another test file of this executable counts allocations the same way,
// its definitions are used and both files read the same counter.
namespace {
std::atomic<std::uint64_t> g_viewer_malloc_calls{0};
}  // namespace

#if defined(MJARM_ADDRESS_SANITIZER)
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));
namespace {
void count_allocation(const volatile void*, std::size_t) {
  g_viewer_malloc_calls.fetch_add(1, std::memory_order_relaxed);
}
void ignore_free(const volatile void*) {}
[[maybe_unused]] const int g_hook_installed =
    __sanitizer_install_malloc_and_free_hooks(count_allocation, ignore_free);
}  // namespace
#else
extern "C" void* __libc_malloc(std::size_t size) noexcept;
extern "C" __attribute__((weak)) void* malloc(std::size_t size) noexcept {
  g_viewer_malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
#endif

namespace mjarm::test {
__attribute__((weak)) std::uint64_t malloc_calls() noexcept {
  return g_viewer_malloc_calls.load(std::memory_order_relaxed);
}
}  // namespace mjarm::test

namespace mjarm {
namespace {

// the panel moved by (dx, dy, dz) [m] and yaw by dyaw [rad] from the initial target
PanelState moved(const ViewerSession& session, double dx, double dy, double dz, double dyaw = 0.0) {
  PanelState panel = session.initial_panel();
  panel.target[slider_x] += dx;
  panel.target[slider_y] += dy;
  panel.target[slider_z] += dz;
  panel.target[slider_yaw] += dyaw;
  return panel;
}

// simulates `seconds` of simulated time
void run_for(ViewerSession& session, double seconds) {
  const int ticks = static_cast<int>(std::lround(seconds / session.control_period()));
  ASSERT_EQ(session.step(ticks), ticks) << session.stats().fault;
}

TEST(ViewerSession, PandaStartsAtHomeWithEveryMode) {
  ViewerSession session(Robot::bundled("panda"));
  EXPECT_EQ(session.site(), "attachment_site");
  EXPECT_EQ(session.mode(), SimulationMode::kinematic);
  for (int m = 0; m < 3; ++m) {
    EXPECT_TRUE(session.available(static_cast<SimulationMode>(m)))
        << session.unavailable_reason(static_cast<SimulationMode>(m));
  }
  EXPECT_FALSE(session.has_gripper());
  EXPECT_DOUBLE_EQ(session.control_period(), 0.01);  // 5 timesteps of 2 ms
  const ViewerStats& s = session.stats();
  // keyframe "home": the flange hangs in front of the base, pointing down
  EXPECT_NEAR(s.X_WE.p.x(), 0.307, 0.01);
  EXPECT_NEAR(s.X_WE.p.z(), 0.59, 0.05);
  EXPECT_LT(s.X_WE.R(2, 2), -0.99);
  EXPECT_LT(s.target_position, 1e-12);  // the initial target is where the end effector is
  EXPECT_LT(s.target_orientation, 1e-9);
  EXPECT_TRUE(panel_target(session.initial_panel()).is_approx(s.X_WE, 1e-9));
}

TEST(ViewerSession, EveryModeReachesThePanelTarget) {
  // tolerances: kinematic IK is exact; the servos and the impedance controller settle close
  const struct {
    SimulationMode mode;
    double seconds, position, orientation;
  } cases[] = {{SimulationMode::kinematic, 1.0, 1e-4, 1e-3},
               {SimulationMode::position, 2.0, 5e-3, 2e-2},
               {SimulationMode::torque, 2.0, 5e-3, 2e-2}};
  for (const auto& c : cases) {
    ViewerSessionOptions options;
    options.mode = c.mode;
    ViewerSession session(Robot::bundled("panda"), options);
    const double start = (session.stats().X_WE.p - Eigen::Vector3d(0.45, 0.1, 0.45)).norm();
    session.set_target(moved(session, 0.45 - session.stats().X_WE.p.x(),
                             0.1 - session.stats().X_WE.p.y(), 0.45 - session.stats().X_WE.p.z(),
                             0.4));
    run_for(session, c.seconds);
    const ViewerStats& s = session.stats();
    EXPECT_GT(start, 0.1);
    EXPECT_LT(s.target_position, c.position) << to_string(c.mode);
    EXPECT_LT(s.target_orientation, c.orientation) << to_string(c.mode);
    EXPECT_TRUE(s.X_WR.is_approx(s.X_WT, 1e-12)) << "the reference has reached the target";
    EXPECT_FALSE(s.faulted) << s.fault;
    EXPECT_NEAR(s.time, c.seconds, 1e-9);
  }
}

TEST(ViewerSession, ASliderJumpBecomesAJerkLimitedMotionThatContinuesWhenTheTargetMoves) {
  // the reference X_WR, one sample per 10 ms tick, through a jump and a second jump made
  // mid-motion: its differences bound the mean velocity, acceleration and jerk over each
  // window (x_{k+1} − x_k = ∫v, second differences a weighted mean of a, third of jerk)
  ViewerSession session(Robot::bundled("panda"));
  const TargetFilterLimits limits;  // the session's defaults
  const double dt = session.control_period();
  std::vector<Eigen::Vector3d> p{session.stats().X_WR.p};
  session.set_target(moved(session, 0.0, 0.2, -0.1));
  for (int k = 0; k < 30; ++k) {
    ASSERT_EQ(session.step(1), 1);
    p.push_back(session.stats().X_WR.p);
  }
  const std::size_t change = p.size() - 1;
  const Eigen::Vector3d v_before = (p[change] - p[change - 1]) / dt;
  EXPECT_GT(v_before.y(), 0.3) << "moving fast towards +y when the target moves";
  session.set_target(moved(session, 0.1, -0.1, 0.0));  // now behind it
  for (int k = 0; k < 300; ++k) {
    ASSERT_EQ(session.step(1), 1);
    p.push_back(session.stats().X_WR.p);
  }
  EXPECT_TRUE(session.stats().X_WR.is_approx(session.stats().X_WT, 0.0)) << "arrived exactly";
  const Eigen::Vector3d v_after = (p[change + 1] - p[change]) / dt;
  EXPECT_GT(v_after.y(), 0.3) << "it continues from the current velocity (braking)";
  EXPECT_LE((v_after - v_before).cwiseAbs().maxCoeff(), limits.acceleration * dt * (1 + 1e-9));
  const double tol = 1 + 1e-6;
  for (std::size_t k = 1; k < p.size(); ++k) {
    EXPECT_LE(((p[k] - p[k - 1]) / dt).cwiseAbs().maxCoeff(), limits.velocity * tol) << k;
    if (k >= 2) {
      const Eigen::Vector3d a = (p[k] - 2 * p[k - 1] + p[k - 2]) / (dt * dt);
      EXPECT_LE(a.cwiseAbs().maxCoeff(), limits.acceleration * tol) << k;
    }
    if (k >= 3) {
      const Eigen::Vector3d j = (p[k] - 3 * p[k - 1] + 3 * p[k - 2] - p[k - 3]) / (dt * dt * dt);
      EXPECT_LE(j.cwiseAbs().maxCoeff(), limits.jerk * tol) << k;
    }
  }
}

TEST(ViewerSession, ModeSwitchCarriesTheStateOver) {
  ViewerSession session(Robot::bundled("panda"));
  session.set_target(moved(session, 0.05, -0.1, -0.05));
  run_for(session, 1.0);
  const Pose before = session.stats().X_WE;
  const double time = session.stats().time;
  session.set_mode(SimulationMode::torque);
  EXPECT_EQ(session.mode(), SimulationMode::torque);
  EXPECT_EQ(session.robot().name(), "panda_torque");
  EXPECT_DOUBLE_EQ(session.control_period(), 0.002);
  EXPECT_TRUE(session.stats().X_WE.is_approx(before, 1e-9));
  EXPECT_TRUE(session.stats().X_WR.is_approx(before, 1e-9)) << "reference restarts at the arm";
  EXPECT_NEAR(session.stats().time, time, 1e-12);
  // the impedance controller holds the pose it took over
  run_for(session, 1.0);
  EXPECT_LT(session.stats().target_position, 5e-3);
  session.set_mode(SimulationMode::position);
  run_for(session, 0.5);
  EXPECT_LT(session.stats().target_position, 5e-3);
  // reset: home again, fault cleared, in the current mode
  session.reset();
  EXPECT_TRUE(session.stats().X_WE.is_approx(panel_target(session.initial_panel()), 1e-6));
  EXPECT_EQ(session.mode(), SimulationMode::position);
  EXPECT_DOUBLE_EQ(session.stats().time, 0.0);
}

TEST(ViewerSession, ModelsWithoutAVariantLackThatMode) {
  // a model from a string has no file beside it: kinematic only; naming the missing variant
  const std::string xml = R"(
    <mujoco model="one">
      <worldbody><body name="base"><joint name="j" type="hinge" axis="0 0 1" range="-2 2"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <site name="tip" pos="0.3 0 0"/></body></worldbody>
      <actuator><motor joint="j"/></actuator>
    </mujoco>)";
  ViewerSession session(Robot::from_string(xml));
  EXPECT_TRUE(session.available(SimulationMode::kinematic));
  EXPECT_FALSE(session.available(SimulationMode::position));
  EXPECT_FALSE(session.available(SimulationMode::torque));
  EXPECT_NE(session.unavailable_reason(SimulationMode::torque).find("torque-motor variant"),
            std::string::npos)
      << session.unavailable_reason(SimulationMode::torque);
  EXPECT_THROW(session.set_mode(SimulationMode::torque), Error);
  ViewerSessionOptions options;
  options.mode = SimulationMode::position;
  EXPECT_THROW(ViewerSession(Robot::from_string(xml), options), Error);
}

TEST(ViewerSession, BadFrameOrKeyframeIsAnError) {
  ViewerSessionOptions options;
  options.site = "end_effctor";
  try {
    ViewerSession session(Robot::bundled("panda"), options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("end_effctor"), std::string::npos) << e.what();
  }
  options.site.clear();
  options.keyframe = "hom";
  EXPECT_THROW(ViewerSession(Robot::bundled("panda"), options), Error);
  // reference limits that are not positive and finite are named
  options.keyframe.clear();
  options.reference_limits.angular_jerk = 0.0;
  try {
    ViewerSession session(Robot::bundled("panda"), options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("angular_jerk"), std::string::npos) << e.what();
  }
  // several sites and none called tcp: the message lists them
  try {
    default_viewer_site(Robot::bundled("dual_arm"));
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--site"), std::string::npos) << e.what();
  }
  EXPECT_EQ(default_viewer_site(Robot::bundled("panda_hand")), "tcp");
}

TEST(ViewerSession, GripperFollowsItsSliderInEveryMode) {
  for (int m = 0; m < 3; ++m) {
    ViewerSessionOptions options;
    options.mode = static_cast<SimulationMode>(m);
    ViewerSession session(Robot::bundled("panda_hand"), options);
    ASSERT_TRUE(session.has_gripper());
    const Robot& robot = session.robot();
    auto width = [&] {
      const mjData& d = session.simulation().data();
      return robot.qpos(d, "finger_left")[0] + robot.qpos(d, "finger_right")[0];
    };
    EXPECT_NEAR(width(), 0.08, 1e-3) << "home: open";
    PanelState panel = session.initial_panel();
    panel.gripper = 0.75;
    session.set_target(panel);
    // the command ramps to the slider: smoothstep over 0.75 × 0.5 s (the default full travel)
    const double T = 0.75 * ViewerSessionOptions{}.gripper_travel_time;
    const double dt = session.control_period();
    const int half = static_cast<int>(std::lround(0.5 * T / dt));
    ASSERT_EQ(session.step(half), half);
    EXPECT_NEAR(session.stats().gripper, 0.75 * smoothstep(half * dt / T).s, 1e-12);
    EXPECT_GT(session.stats().gripper, 0.2);
    EXPECT_LT(session.stats().gripper, 0.55);
    run_for(session, 1.0);
    EXPECT_EQ(session.stats().gripper, 0.75);
    EXPECT_NEAR(width(), 0.02, 2e-3) << to_string(options.mode);
    EXPECT_LT(session.stats().target_position, 5e-3) << "the arm holds still meanwhile";
  }
}

TEST(ViewerSession, StepAllocatesNothing) {
  for (int m = 0; m < 3; ++m) {
    ViewerSessionOptions options;
    options.mode = static_cast<SimulationMode>(m);
    ViewerSession session(Robot::bundled("panda_hand"), options);
    PanelState panel = moved(session, 0.1, 0.1, -0.1, 0.3);
    panel.gripper = 0.5;
    session.set_target(panel);
    session.step(2);  // warm-up
    const std::uint64_t before = test::malloc_calls();
    const int done = session.step(50);
    const std::uint64_t after = test::malloc_calls();
    EXPECT_EQ(done, 50);
    EXPECT_EQ(after - before, 0u) << to_string(options.mode) << " mode allocated";
  }
}

}  // namespace
}  // namespace mjarm
