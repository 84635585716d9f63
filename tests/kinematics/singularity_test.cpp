#include "mjarm/kinematics/singularity.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

/// Planar two-link arm (0.5 m, 0.3 m) with keyframes; w = 0.15·|sin q2| for the position block.
constexpr const char* kPlanarKeys = R"(
<mujoco model="planar_keys">
  <compiler angle="radian"/>
  <worldbody>
    <body name="l1">
      <joint name="q1" type="hinge" axis="0 0 1" range="-1 2" limited="true"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.02"/>
      <body name="l2" pos="0.5 0 0">
        <joint name="q2" type="hinge" axis="0 0 1" range="-0.5 1.5" limited="true"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <site name="tip" pos="0.3 0 0"/>
      </body>
    </body>
  </worldbody>
  <keyframe>
    <key name="straight" qpos="0.3 0"/>
    <key name="bent" qpos="0.1 1.2"/>
    <key qpos="0 0.002"/>
  </keyframe>
</mujoco>
)";

class SingularityTest : public ::testing::Test {
 protected:
  Robot robot_ = Robot::from_string(kPlanarKeys);
  Chain chain_{robot_, "tip"};
  ManipulabilityOptions options_{.block = JacobianBlock::position};
};

TEST_F(SingularityTest, ReportsStandardAndExtraConfigurations) {
  const SingularityReport report =
      singularity_report(chain_, {{"mine", Eigen::Vector2d(0.0, 0.9)}}, options_);
  ASSERT_EQ(report.entries.size(), 6u);
  const char* names[] = {"qpos0", "center", "straight", "bent", "keyframe 2", "mine"};
  const double q2[] = {0.0, 0.5, 0.0, 1.2, 0.002, 0.9};  // qpos0: elbow straight
  const SingularityStatus status[] = {SingularityStatus::singular,      SingularityStatus::regular,
                                      SingularityStatus::singular,      SingularityStatus::regular,
                                      SingularityStatus::near_singular, SingularityStatus::regular};
  for (std::size_t k = 0; k < report.entries.size(); ++k) {
    const SingularityEntry& e = report.entries[k];
    EXPECT_EQ(e.name, names[k]);
    EXPECT_DOUBLE_EQ(e.q[1], q2[k]) << e.name;
    EXPECT_NEAR(e.manipulability, 0.15 * std::abs(std::sin(q2[k])), 1e-14) << e.name;
    EXPECT_EQ(e.status, status[k]) << e.name;
    EXPECT_EQ(e.singular_values.size(), 2);
    EXPECT_DOUBLE_EQ(e.sigma_min, e.singular_values[1]);
    if (e.status == SingularityStatus::singular) {
      EXPECT_TRUE(std::isinf(e.condition_number));
    } else {
      EXPECT_DOUBLE_EQ(e.condition_number, e.singular_values[0] / e.sigma_min);
    }
  }
  EXPECT_DOUBLE_EQ(report.entries[1].q[0], 0.5);  // centre of [-1, 2]
}

TEST_F(SingularityTest, ThresholdDecidesNearSingular) {
  // keyframe 2 (q2 = 0.002) becomes regular when the threshold is lowered below its 1/κ
  ManipulabilityOptions loose = options_;
  loose.near_singular_threshold = 1e-4;
  const SingularityReport report = singularity_report(chain_, {}, loose);
  EXPECT_EQ(report.entries[4].status, SingularityStatus::regular);
  EXPECT_EQ(report.entries[2].status, SingularityStatus::singular);
}

TEST_F(SingularityTest, RejectsBadConfigurationNamingIt) {
  try {
    singularity_report(chain_, {{"too_short", Eigen::VectorXd::Zero(1)}});
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("too_short"), std::string::npos) << e.what();
  }
  Eigen::Vector2d nan(0.0, std::nan(""));
  EXPECT_THROW(singularity_report(chain_, {{"nan", nan}}), Error);
  EXPECT_THROW(scan_singularities(chain_, 0, 1), Error);
}

TEST_F(SingularityTest, ScanKeepsTheLowestSigmaDeterministically) {
  const Robot tricky = Robot::from_string(test::kTrickyArm);
  const Chain chain(tricky, "tool");
  const std::size_t samples = 2000, keep = 7;
  const SingularityScan scan = scan_singularities(chain, samples, 42, keep);
  ASSERT_EQ(scan.worst.size(), keep);
  // brute force over the same samples
  Manipulability m(chain);
  const JointSampler sampler(chain);
  std::mt19937_64 rng(42);
  std::vector<double> sigma(samples);
  std::size_t singular = 0, near = 0;
  Eigen::VectorXd q(chain.size());
  for (std::size_t s = 0; s < samples; ++s) {
    sampler.sample(rng, q);
    const ManipulabilityResult r = m.evaluate(q);
    sigma[s] = r.sigma_min;
    singular += r.status == SingularityStatus::singular;
    near += r.status == SingularityStatus::near_singular;
  }
  std::vector<double> sorted = sigma;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < keep; ++k) {
    EXPECT_EQ(scan.worst[k].sigma_min, sorted[k]);
    const std::size_t index = std::stoul(scan.worst[k].name.substr(7));  // "sample <i>"
    EXPECT_EQ(sigma[index], sorted[k]);
  }
  EXPECT_EQ(scan.singular_count, singular);
  EXPECT_EQ(scan.near_singular_count, near);
  // same seed, same bits; another seed, other samples
  const SingularityScan again = scan_singularities(chain, samples, 42, keep);
  for (std::size_t k = 0; k < keep; ++k) EXPECT_EQ(again.worst[k].q, scan.worst[k].q);
  EXPECT_NE(scan_singularities(chain, samples, 43, keep).worst[0].q, scan.worst[0].q);
}

TEST_F(SingularityTest, ScanReportsProgressAndStopsWhenAsked) {
  std::vector<std::size_t> calls;
  const SingularityScan full =
      scan_singularities(chain_, 5000, 9, 3, {}, {}, [&](std::size_t done, std::size_t total) {
        EXPECT_EQ(total, 5000u);
        calls.push_back(done);
      });
  EXPECT_EQ(full.status, SamplingStatus::complete);
  ASSERT_FALSE(calls.empty());
  EXPECT_LE(calls.size(), 101u);
  EXPECT_EQ(calls.back(), 5000u);
  EXPECT_TRUE(std::is_sorted(calls.begin(), calls.end()));
  int asked = 0;
  const SingularityScan stopped =
      scan_singularities(chain_, 5000, 9, 3, {}, {}, nullptr, [&] { return ++asked > 2; });
  EXPECT_EQ(stopped.status, SamplingStatus::interrupted);
  EXPECT_EQ(stopped.samples, 2000u);  // asked before samples 0, 1000 and 2000
  EXPECT_LE(stopped.singular_count + stopped.near_singular_count,
            full.singular_count + full.near_singular_count);
}

TEST_F(SingularityTest, ScanFindsTheStraightElbowRegion) {
  // with q2 in [-0.5, 1.5] the worst samples cluster around the straight elbow q2 = 0
  const SingularityScan scan = scan_singularities(chain_, 5000, 3, 5, options_);
  for (const SingularityEntry& e : scan.worst) {
    EXPECT_LT(std::abs(e.q[1]), 4e-3);
    EXPECT_NEAR(e.manipulability, 0.15 * std::abs(std::sin(e.q[1])), 1e-14);
  }
  EXPECT_GT(scan.near_singular_count, 0u);
}

TEST(SingularityBundled, Ur5eStandardConfigurations) {
  // DH zero angles put the ur5e in both its elbow and wrist singularities; its home keyframe
  // is regular
  const Robot robot = Robot::bundled("ur5e");
  const Chain chain(robot, "attachment_site");
  const SingularityReport report = singularity_report(chain);
  ASSERT_EQ(report.entries.size(), 3u);
  EXPECT_EQ(report.entries[0].name, "qpos0");
  EXPECT_EQ(report.entries[0].status, SingularityStatus::singular);
  EXPECT_EQ(report.entries[1].name, "center");  // ranges are symmetric: all zeros again
  EXPECT_EQ(report.entries[1].status, SingularityStatus::singular);
  EXPECT_EQ(report.entries[2].name, "home");
  EXPECT_EQ(report.entries[2].status, SingularityStatus::regular);
  EXPECT_GT(report.entries[2].manipulability, 1e-3);
  // at zero the wrist axes are parallel too, but the one direction lost is the stretched elbow's
  for (int k : {0, 1}) {
    EXPECT_EQ(report.entries[k].kinds, std::vector<SingularityKind>{SingularityKind::elbow});
    EXPECT_TRUE(report.entries[k].below_sigma_min && report.entries[k].above_condition_number);
  }
  EXPECT_TRUE(report.entries[2].kinds.empty());
  EXPECT_FALSE(report.entries[2].below_sigma_min || report.entries[2].above_condition_number);
}

TEST(SingularityBundled, Arm6ReportNamesEachKind) {
  const Robot robot = Robot::bundled("arm6");
  const Chain chain(robot, "grip");
  const Eigen::VectorXd home = chain.gather(robot.model().key_qpos);
  Eigen::VectorXd wrist = home, elbow = home;
  wrist[4] = 0.0;
  elbow[2] = 0.0;
  const SingularityReport report =
      singularity_report(chain, {{"wrist", wrist}, {"elbow", elbow}, {"zero", chain.center()}});
  ASSERT_EQ(report.entries.size(), 6u);  // qpos0, center, home, then the three
  using Kinds = std::vector<SingularityKind>;
  EXPECT_EQ(report.entries[2].name, "home");
  EXPECT_TRUE(report.entries[2].kinds.empty());
  EXPECT_EQ(report.entries[3].kinds, Kinds{SingularityKind::wrist});
  EXPECT_EQ(report.entries[4].kinds, Kinds{SingularityKind::elbow});
  // all joints at 0: arm upright, wrist aligned on the first axis
  EXPECT_EQ(report.entries[5].kinds,
            (Kinds{SingularityKind::wrist, SingularityKind::elbow, SingularityKind::shoulder}));
  for (const SingularityEntry& e : report.entries) {
    EXPECT_EQ(e.null_direction.size(), 6) << e.name;
    EXPECT_NEAR(e.null_direction.norm(), 1.0, 1e-12) << e.name;
  }
  EXPECT_DOUBLE_EQ(report.thresholds.sigma_min, 0.01);
  EXPECT_DOUBLE_EQ(report.thresholds.condition_number, 100.0);
}

TEST(SingularityBundled, ScanCountsBothThresholds) {
  const Robot robot = Robot::bundled("ur5e");
  const Chain chain(robot, "attachment_site");
  const SingularityScan scan = scan_singularities(chain, 3000, 5, 3);
  // κ > 100 is the near-singular class; σmin < 0.01 adds to it
  EXPECT_GE(scan.flagged_count, scan.singular_count + scan.near_singular_count);
  EXPECT_GT(scan.flagged_count, 0u);
  ASSERT_EQ(scan.worst.size(), 3u);
  for (const SingularityEntry& e : scan.worst) {
    EXPECT_TRUE(e.below_sigma_min) << e.name;
    EXPECT_FALSE(e.kinds.empty()) << e.name;
  }
  // with σmax ≈ 2, σmin < 0.01 implies κ > 100: the absolute threshold alone flags fewer
  const SingularityScan absolute =
      scan_singularities(chain, 3000, 5, 0, {}, {.condition_number = 1e300});
  EXPECT_GT(absolute.flagged_count, 0u);
  EXPECT_LT(absolute.flagged_count, scan.flagged_count);
}

}  // namespace
}  // namespace mjarm
