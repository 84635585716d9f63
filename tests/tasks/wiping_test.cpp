// The wiping task (mjarm/tasks/wiping*.hpp): a stroke at a constant normal force with either law,
// the force loop against the feed-forward alone (whose error is the normal spring's pull towards
// the believed table: a physical cross-check), joint friction, and bad input.
#include "mjarm/tasks/wiping/wiping.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "ik/malloc_counter.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::error_of;
using ::testing::HasSubstr;

std::shared_ptr<const WipingScene> shared_wiping_scene() {
  static const auto s = std::make_shared<const WipingScene>(build_wiping_scene());
  return s;
}

/// A shorter stroke than the default (0.15 m at 0.05 m/s): about 2 400 control ticks.
WipingOptions quick_wipe(WipingLaw law, double gain, std::uint64_t seed) {
  WipingOptions o;
  o.scene = shared_wiping_scene();
  o.control.law = law;
  o.force_loop.gain = gain;
  o.seed = seed;
  o.path.length = 0.15;
  o.motion.approach_time = 0.6;
  o.motion.start_height = 0.02;
  return o;
}

TEST(Wiping, BothLawsWipeTheStrokeAtTheSetForce) {
  for (const WipingLaw law : {WipingLaw::cic, WipingLaw::osc}) {
    const WipingReport r = run_wiping(quick_wipe(law, 10.0, 3));
    const WipingMetrics& m = r.metrics;
    EXPECT_EQ(r.outcome, WipingOutcome::wiped) << to_string(law) << ": " << wiping_result_line(r);
    EXPECT_GT(m.samples, 1000);
    EXPECT_NEAR(m.mean_force, 10.0, 0.1) << to_string(law);
    EXPECT_LT(m.force_rms_error, 0.5) << to_string(law);
    EXPECT_EQ(m.contact_fraction, 1.0) << to_string(law);
    EXPECT_LT(m.path_max_error, 1e-3) << to_string(law);
    EXPECT_FALSE(m.arm_contact);
    EXPECT_GE(m.path_max_error, m.path_rms_error);
    EXPECT_GE(m.force_max_error, m.force_rms_error);
  }
}

TEST(Wiping, TheForceLoopRemovesTheNormalSpringsPullTowardsTheBelievedTable) {
  // seed 3 believes the table 2.5 mm low: the reference sits below the surface, and the normal
  // spring adds K_z·(true − believed) to the fed-forward force; the loop integrates it away
  const WipingReport loop = run_wiping(quick_wipe(WipingLaw::cic, 10.0, 3));
  const WipingReport feed_forward = run_wiping(quick_wipe(WipingLaw::cic, 0.0, 3));
  const double offset = loop.plan.true_height - loop.plan.believed_height;
  ASSERT_GT(offset, 0.002);
  const double spring = WipingControl{}.normal_stiffness * offset;
  EXPECT_NEAR(feed_forward.metrics.mean_force - 10.0, spring, 0.25 * spring);
  EXPECT_NEAR(loop.metrics.mean_force, 10.0, 0.1);
  EXPECT_LT(loop.metrics.force_rms_error, 0.5 * feed_forward.metrics.force_rms_error);
}

TEST(Wiping, WithJointFrictionCicsFeedForwardKeepsThePathThatOscLoses) {
  WipingOptions cic = quick_wipe(WipingLaw::cic, 10.0, 1);
  cic.scene = nullptr;
  cic.surface.joint_friction = true;
  WipingOptions osc = cic;
  osc.control.law = WipingLaw::osc;
  const WipingReport with_ff = run_wiping(cic);
  const WipingReport without = run_wiping(osc);
  EXPECT_EQ(with_ff.outcome, WipingOutcome::wiped) << wiping_result_line(with_ff);
  EXPECT_EQ(without.outcome, WipingOutcome::off_path) << wiping_result_line(without);
  EXPECT_GT(without.metrics.path_max_error, 1.5 * with_ff.metrics.path_max_error);
}

TEST(Wiping, TheTasksUpdateAllocatesNothingAfterTheFirstTickAndPressesAsPlanned) {
  const WipingScene& scene = *shared_wiping_scene();
  const WipingMotion motion;
  const WipingPlan plan = plan_wiping(scene, WipingPath{}, motion, 1);
  DataPtr d = scene.robot.make_data();
  mj_forward(&scene.robot.model(), d.get());
  WipingTask task(scene, plan, motion, WipingForceLoop{}, 1);
  Reference r;
  task.update(*d, r);
  const std::uint64_t before = test::malloc_calls();
  double pressing = 0.0;
  for (int k = 0; 0.01 * k < plan.duration() - 1e-6; ++k) {
    d->time = 0.01 * k;
    ASSERT_TRUE(task.update(*d, r)) << d->time;
    if (task.phase() == WipingPhase::stroke) pressing = -r.task.F_ext[2];
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
  // nothing touches the table here: the loop adds up to F_d, the bound of its integral
  EXPECT_NEAR(pressing, 2.0 * motion.force, 1e-9);
  d->time = plan.duration();
  EXPECT_FALSE(task.update(*d, r));
}

TEST(Wiping, RefusesAStrokeOffTheTableAndASceneOfAnotherSurface) {
  WipingOptions o = quick_wipe(WipingLaw::cic, 10.0, 1);
  o.path.center = {0.75, 0.0};
  o.path.heading = 0.0;
  EXPECT_THAT(error_of([&] { run_wiping(o); }), HasSubstr("the stroke's end (0.825, 0) m is off"));
  o = quick_wipe(WipingLaw::cic, 10.0, 1);
  o.surface.friction = 0.5;
  EXPECT_THAT(error_of([&] { run_wiping(o); }), HasSubstr("built for another surface"));
  o = quick_wipe(WipingLaw::cic, 10.0, 1);
  o.motion.force = -1.0;
  EXPECT_THAT(error_of([&] { run_wiping(o); }), HasSubstr("force"));
}

}  // namespace
}  // namespace mjarm
