// Domain randomization: factors within their ranges, drawn from the episode's random state,
// written into the simulation's own copy only, never compounding; the physics feels them.

#include "mjarm/env/randomization.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "env/env_test_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/env/environment.hpp"

namespace mjarm {
namespace {

using test::expect_error_containing;

EnvironmentOptions randomized(const RandomizationOptions& r) {
  EnvironmentOptions o;
  o.action_space = ActionSpace::joint_torques;
  o.observations = {"joint_positions", "object_pose"};
  o.randomization = r;
  return o;
}

RandomizationOptions everything() {
  RandomizationOptions r;
  r.mass = 0.2;
  r.friction = 0.3;
  r.damping = 0.4;
  r.gain = 0.1;
  r.object_size = 0.25;
  return r;
}

void expect_within(const Eigen::VectorXd& factors, double range, const char* what) {
  ASSERT_GT(factors.size(), 0) << what;
  EXPECT_GE(factors.minCoeff(), 1.0 - range) << what;
  EXPECT_LE(factors.maxCoeff(), 1.0 + range) << what;
  EXPECT_GT(factors.maxCoeff() - factors.minCoeff(), 0.0) << what;  // not all the same
}

TEST(DomainRandomizer, ScalesEveryParameterWithinItsRange) {
  Environment env(std::make_unique<test::HookTask>(), randomized(everything()));
  env.reset(3);
  const DomainRandomizer& r = *env.randomizer();
  const mjModel& m = env.simulation().model();
  const mjModel& m0 = env.task().robot().model();
  expect_within(r.mass_factors().tail(m.nbody - 1), 0.2, "mass");
  expect_within(r.friction_factors(), 0.3, "friction");
  expect_within(r.damping_factors(), 0.4, "damping");
  expect_within(r.gain_factors(), 0.1, "gain");
  ASSERT_EQ(r.size_factors().size(), 1);
  const double s = r.size_factors()[0];
  EXPECT_GE(s, 0.75);
  EXPECT_LE(s, 1.25);
  // the copy holds nominal × factor; the robot's model keeps its values
  for (int b = 1; b < m.nbody; ++b) {
    const bool object = b == m0.geom_bodyid[env.task().object_geoms()[0]];
    const double size_mass = object ? s * s * s : 1.0;
    EXPECT_DOUBLE_EQ(m.body_mass[b], m0.body_mass[b] * r.mass_factors()[b] * size_mass) << b;
    EXPECT_DOUBLE_EQ(m.body_inertia[3 * b + 1], m0.body_inertia[3 * b + 1] * r.mass_factors()[b] *
                                                    (object ? s * s * s * s * s : 1.0));
  }
  for (int g = 0; g < m.ngeom; ++g)
    EXPECT_DOUBLE_EQ(m.geom_friction[3 * g], m0.geom_friction[3 * g] * r.friction_factors()[g]);
  for (int v = 0; v < m.nv; ++v)
    EXPECT_DOUBLE_EQ(m.dof_damping[v], m0.dof_damping[v] * r.damping_factors()[v]);
  for (int a = 0; a < m.nu; ++a)
    EXPECT_DOUBLE_EQ(m.actuator_gainprm[mjNGAIN * a],
                     m0.actuator_gainprm[mjNGAIN * a] * r.gain_factors()[a]);
  const int box = env.task().object_geoms()[0];
  EXPECT_DOUBLE_EQ(m.geom_size[3 * box], m0.geom_size[3 * box] * s);
  EXPECT_DOUBLE_EQ(m.geom_rbound[box], m0.geom_rbound[box] * s);
  // derived constants follow (mj_setConst): the subtree mass of the world is the total mass
  double total = 0.0;
  for (int b = 1; b < m.nbody; ++b) total += m.body_mass[b];
  EXPECT_NEAR(m.body_subtreemass[0], total, 1e-12);
  EXPECT_NE(m.body_subtreemass[0], m0.body_subtreemass[0]);
}

TEST(DomainRandomizer, DrawsFromTheEpisodeSeedAndNeverCompounds) {
  Environment env(std::make_unique<test::HookTask>(), randomized(everything()));
  env.reset(3);
  const Eigen::VectorXd mass3 = env.randomizer()->mass_factors();
  const double box_mass3 = env.simulation().model().body_mass[2];
  env.reset(4);
  EXPECT_NE(env.randomizer()->mass_factors(), mass3);
  env.reset(3);
  EXPECT_EQ(env.randomizer()->mass_factors(), mass3);
  EXPECT_EQ(env.simulation().model().body_mass[2], box_mass3);  // from nominal, not compounded
  // the task's own draws do not depend on the randomization (separate generators)
  Environment plain(std::make_unique<test::HookTask>(), randomized(RandomizationOptions{}));
  plain.reset(3);
  EXPECT_EQ(static_cast<const test::HookTask&>(plain.task()).drawn,
            static_cast<const test::HookTask&>(env.task()).drawn);
  EXPECT_EQ(plain.randomizer(), nullptr);
  EXPECT_FALSE(plain.simulation().owns_model());
}

TEST(DomainRandomizer, ThePhysicsFeelsIt) {
  // a bigger box sits higher; more damping slows the arm under the same torques
  RandomizationOptions sizes;
  sizes.object_size = 0.5;
  Environment env(std::make_unique<test::HookTask>(), randomized(sizes));
  const std::vector<double> push{2.0, 0.0};
  double z_big = 0.0, z_small = 0.0;
  for (std::uint64_t seed = 0; seed < 40 && (z_big == 0.0 || z_small == 0.0); ++seed) {
    env.reset(seed);
    TimeStep ts;
    for (int k = 0; k < 25; ++k) ts = env.step(push);  // the box settles on the floor
    const double s = env.randomizer()->size_factors()[0];
    const double z = ts.observation["object_pose"][2];
    EXPECT_NEAR(z, 0.05 * s, 2e-3) << "size factor " << s;
    if (s > 1.2) z_big = z;
    if (s < 0.8) z_small = z;
  }
  EXPECT_GT(z_big, z_small);
}

TEST(DomainRandomizer, ResetStaysAllocationFreeAndDeterministic) {
  Environment a(std::make_unique<test::HookTask>(), randomized(everything()));
  Environment b(std::make_unique<test::HookTask>(), randomized(everything()));
  a.reset(1);
  const std::uint64_t before = test::malloc_calls();
  a.reset(9);
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  b.reset(9);
  const std::vector<double> push{3.0, -1.0};
  TimeStep ta, tb;
  for (int k = 0; k < 20; ++k) {
    ta = a.step(push);
    tb = b.step(push);
  }
  EXPECT_EQ(std::memcmp(ta.observation.values().data(), tb.observation.values().data(),
                        ta.observation.values().size_bytes()),
            0);
}

TEST(DomainRandomizer, BadRangesAreErrors) {
  RandomizationOptions r;
  r.mass = 1.0;
  expect_error_containing([&] { r.check(); }, {"randomization: mass must be in [0, 1)", "got 1"});
  r.mass = -0.1;
  expect_error_containing([&] { r.check(); }, {"mass"});
  r.mass = 0.0;
  r.friction = std::nan("");
  expect_error_containing([&] { r.check(); }, {"friction"});
  EXPECT_FALSE(RandomizationOptions{}.any());
  // object sizes on a task without objects
  RandomizationOptions sizes;
  sizes.object_size = 0.1;
  expect_error_containing(
      [&] {
        EnvironmentOptions o;
        o.randomization = sizes;
        Environment env(test::reach_task(), o);
      },
      {"object_size", "no objects"});
  const Robot robot = Robot::from_string(test::kHookArm);
  expect_error_containing([&] { DomainRandomizer d(robot.model(), sizes, {99}); },
                          {"object geom id 99 out of range"});
}

}  // namespace
}  // namespace mjarm
