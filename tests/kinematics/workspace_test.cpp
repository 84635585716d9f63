#include "mjarm/kinematics/workspace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "support/file_size_limit.hpp"
#include "support/files.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

/// Planar arm (0.5 m, 0.3 m) whose base sits at (0.2, -0.1, 0.4); q1 unlimited, q2 limited.
constexpr const char* kPlanar = R"(
<mujoco model="planar_ws">
  <compiler angle="radian"/>
  <worldbody>
    <body name="l1" pos="0.2 -0.1 0.4">
      <joint name="q1" type="hinge" axis="0 0 1"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.02"/>
      <body name="l2" pos="0.5 0 0">
        <joint name="q2" type="hinge" axis="0 0 1" range="-2.5 2.5" limited="true"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <site name="tip" pos="0.3 0 0"/>
      </body>
    </body>
  </worldbody>
</mujoco>
)";

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

class WorkspaceTest : public ::testing::Test {
 protected:
  Robot planar_ = Robot::from_string(kPlanar);
  Robot tricky_ = Robot::from_string(test::kTrickyArm);
};

TEST_F(WorkspaceTest, SamplerStaysWithinLimitsAndUsesPiForUnlimited) {
  const Chain chain(planar_, "tip");
  const JointSampler sampler(chain);
  EXPECT_EQ(sampler.lower()[0], -std::numbers::pi);
  EXPECT_EQ(sampler.upper()[0], std::numbers::pi);
  EXPECT_EQ(sampler.lower()[1], -2.5);
  std::mt19937_64 rng(5);
  Eigen::VectorXd q(2);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(10), hi = Eigen::Vector2d::Constant(-10);
  for (int s = 0; s < 10000; ++s) {
    sampler.sample(rng, q);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  EXPECT_GE(lo[0], -std::numbers::pi);
  EXPECT_LT(hi[0], std::numbers::pi);
  EXPECT_GE(lo[1], -2.5);
  EXPECT_LT(hi[1], 2.5);
  EXPECT_LT(lo[1], -2.49);  // and covers the range
  EXPECT_GT(hi[1], 2.49);
}

TEST_F(WorkspaceTest, PlanarArmReachMatchesLinkLengths) {
  const Chain chain(planar_, "tip");
  const WorkspaceResult ws = sample_workspace(chain, {.samples = 20000, .seed = 7});
  ASSERT_EQ(ws.points.size(), 20000u);
  EXPECT_LT((ws.p_WB - Eigen::Vector3d(0.2, -0.1, 0.4)).norm(), 1e-15);
  // |tip − base|² = l1² + l2² + 2 l1 l2 cos q2, with |q2| ≤ 2.5: reach in [r(2.5), 0.8]
  const double r_min = std::sqrt(0.25 + 0.09 + 0.3 * std::cos(2.5));
  for (const WorkspacePoint& p : ws.points) {
    const double r = (p.p_WE - ws.p_WB).norm();
    EXPECT_LE(r, 0.8 + 1e-12);
    EXPECT_GE(r, r_min - 1e-12);
    EXPECT_NEAR(p.p_WE.z(), 0.4, 1e-12);
  }
  EXPECT_GT(ws.max_reach_from_base, 0.799);
  EXPECT_LE(ws.max_reach_from_base, 0.8 + 1e-12);
  // the disk of radius 0.8 around the base bounds the box, and is nearly filled
  EXPECT_LT((ws.upper.head<2>() - ws.p_WB.head<2>() - Eigen::Vector2d(0.8, 0.8)).norm(), 2e-3);
  EXPECT_LT((ws.lower.head<2>() - ws.p_WB.head<2>() + Eigen::Vector2d(0.8, 0.8)).norm(), 2e-3);
  // q1 uniform over a full turn: the centroid sits on the base
  EXPECT_LT((ws.centroid - ws.p_WB).norm(), 0.01);
  // position manipulability of the planar arm is l1·l2·|sin q2| ≤ 0.15
  EXPECT_LE(ws.max_manipulability, 0.15 + 1e-12);
  EXPECT_GT(ws.max_manipulability, 0.1499);
  EXPECT_GE(ws.min_manipulability, 0.0);
}

TEST_F(WorkspaceTest, StatisticsAgreeWithPointsAndForwardKinematics) {
  const Chain chain(tricky_, "tool");
  const WorkspaceResult ws = sample_workspace(chain, {.samples = 3000, .seed = 11});
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo, sum = Eigen::Vector3d::Zero();
  double reach_origin = 0, reach_base = 0, w_sum = 0;
  for (const WorkspacePoint& p : ws.points) {
    lo = lo.cwiseMin(p.p_WE);
    hi = hi.cwiseMax(p.p_WE);
    sum += p.p_WE;
    reach_origin = std::max(reach_origin, p.p_WE.norm());
    reach_base = std::max(reach_base, (p.p_WE - ws.p_WB).norm());
    w_sum += p.manipulability;
  }
  EXPECT_EQ(ws.lower, lo);
  EXPECT_EQ(ws.upper, hi);
  EXPECT_LT((ws.centroid - sum / 3000.0).norm(), 1e-12);
  EXPECT_EQ(ws.max_reach_from_origin, reach_origin);
  EXPECT_EQ(ws.max_reach_from_base, reach_base);
  EXPECT_NEAR(ws.mean_manipulability, w_sum / 3000.0, 1e-12);
  // the base is j1's anchor: the base body's origin
  EXPECT_LT((ws.p_WB - Eigen::Vector3d(0.1, -0.2, 0.3)).norm(), 1e-15);
  // replay the sampler: every point is the frame position of its sample
  const JointSampler sampler(chain);
  std::mt19937_64 rng(11);
  Eigen::VectorXd q(chain.size());
  Manipulability m(chain, {.block = JacobianBlock::position});
  for (std::size_t s = 0; s < 200; ++s) {
    sampler.sample(rng, q);
    EXPECT_LT((forward_kinematics(chain, q).p - ws.points[s].p_WE).norm(), 1e-15);
    EXPECT_EQ(m.evaluate(q).manipulability, ws.points[s].manipulability);
  }
}

TEST_F(WorkspaceTest, SameSeedSameBits) {
  const Chain chain(tricky_, "tool");
  const WorkspaceResult a = sample_workspace(chain, {.samples = 500, .seed = 99});
  const WorkspaceResult b = sample_workspace(chain, {.samples = 500, .seed = 99});
  const WorkspaceResult c = sample_workspace(chain, {.samples = 500, .seed = 100});
  for (std::size_t s = 0; s < 500; ++s) {
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(same_bits(a.points[s].p_WE[k], b.points[s].p_WE[k]));
    EXPECT_TRUE(same_bits(a.points[s].manipulability, b.points[s].manipulability));
  }
  EXPECT_NE(a.points[0].p_WE, c.points[0].p_WE);
  // statistics do not depend on keeping the points or on computing manipulability
  const WorkspaceResult lean = sample_workspace(
      chain, {.samples = 500, .seed = 99, .compute_manipulability = false, .keep_points = false});
  EXPECT_TRUE(lean.points.empty());
  EXPECT_EQ(lean.lower, a.lower);
  EXPECT_EQ(lean.upper, a.upper);
  EXPECT_EQ(lean.max_reach_from_base, a.max_reach_from_base);
  EXPECT_EQ(lean.max_manipulability, 0.0);
}

// every 1 % of the samples, and at least every 1000: about a hundred calls for a small run, and a
// long one still moves (120 000: 1 % is 1200, so the thousand is what binds)
TEST_F(WorkspaceTest, ProgressIsReportedEveryPercentOrThousandSamples) {
  const Chain chain(planar_, "tip");
  for (std::size_t total : {1u, 37u, 100u, 1001u, 25000u, 120000u}) {
    std::vector<std::size_t> calls;
    WorkspaceOptions options;
    options.samples = total;
    options.progress = [&](std::size_t done, std::size_t all) {
      EXPECT_EQ(all, total);
      calls.push_back(done);
    };
    sample_workspace(chain, options);
    ASSERT_FALSE(calls.empty());
    EXPECT_LE(calls.size(), std::max<std::size_t>(101u, total / 1000 + 1)) << total;
    EXPECT_EQ(calls.back(), total);
    EXPECT_TRUE(std::is_sorted(calls.begin(), calls.end()));
    for (std::size_t k = 1; k < calls.size(); ++k) EXPECT_LE(calls[k] - calls[k - 1], 1000u);
    if (total >= 100) {
      EXPECT_GE(calls.size(), 50u);
    }
  }
}

TEST_F(WorkspaceTest, CsvRoundTripsAndBadPathThrows) {
  const Chain chain(planar_, "tip");
  const WorkspaceResult ws = sample_workspace(chain, {.samples = 50, .seed = 3});
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("mjarm_workspace_test_" + std::to_string(::getpid()) + ".csv");
  ws.write_csv(path);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,z,manipulability");
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    double v[4];
    char comma;
    row >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3];
    ASSERT_TRUE(row) << line;
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(same_bits(v[k], ws.points[rows].p_WE[k]));
    EXPECT_TRUE(same_bits(v[3], ws.points[rows].manipulability));
    ++rows;
  }
  EXPECT_EQ(rows, 50u);
  std::filesystem::remove(path);

  const std::filesystem::path bad = "/nonexistent_dir_mjarm/ws.csv";
  try {
    ws.write_csv(bad);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
}

TEST_F(WorkspaceTest, CsvOnAFullDiskLeavesTheOldFileAndNamesTheReason) {
  const Chain chain(planar_, "tip");
  const WorkspaceResult ws = sample_workspace(chain, {.samples = 500, .seed = 3});  // ~40 KB
  const std::filesystem::path dir = test::scratch() / "workspace_full";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / "ws.csv";
  std::ofstream(path) << "old content\n";
  const test::LimitedRun child = test::with_file_size_limit(4096, [&] {
    ws.write_csv(path);
    return std::string("written");
  });
  ASSERT_EQ(child.exit_code, 1) << child.out;
  EXPECT_NE(child.err.find(path.string()), std::string::npos) << child.err;
  EXPECT_NE(child.err.find("File too large"), std::string::npos) << child.err;
  // never a truncated CSV: the old file as it was, and no temporary file beside it
  EXPECT_EQ(test::slurp(path), "old content\n");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
  // a device that refuses every byte (ENOSPC) is reported too
  try {
    ws.write_csv("/dev/full");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
  }
}

TEST_F(WorkspaceTest, RejectsBadOptions) {
  const Chain chain(planar_, "tip");
  EXPECT_THROW(sample_workspace(chain, {.samples = 0}), Error);
  WorkspaceOptions options;
  options.manipulability.singular_tolerance = -1.0;
  EXPECT_THROW(sample_workspace(chain, options), Error);
}

TEST_F(WorkspaceTest, AStopRequestEndsTheRunWithTheSamplesDrawn) {
  const Chain chain(planar_, "tip");
  WorkspaceOptions options;
  options.samples = 10000;
  int asked = 0;
  options.stop = [&] { return ++asked > 3; };  // stop at the fourth question: after 3000
  const WorkspaceResult stopped = sample_workspace(chain, options);
  EXPECT_EQ(stopped.status, SamplingStatus::interrupted);
  EXPECT_EQ(stopped.samples, 3000u);
  EXPECT_EQ(stopped.points.size(), 3000u);
  // the statistics are those of the samples drawn: the same as a run of 3000
  const WorkspaceResult first = sample_workspace(chain, {.samples = 3000});
  EXPECT_EQ(first.status, SamplingStatus::complete);
  EXPECT_EQ(stopped.lower, first.lower);
  EXPECT_EQ(stopped.upper, first.upper);
  EXPECT_EQ(stopped.centroid, first.centroid);
  EXPECT_STREQ(to_string(stopped.status), "interrupted");
  // stopped before the first sample: nothing drawn, no NaN statistics
  options.stop = [] { return true; };
  const WorkspaceResult none = sample_workspace(chain, options);
  EXPECT_EQ(none.samples, 0u);
  EXPECT_TRUE(none.centroid.allFinite());
  EXPECT_TRUE(none.lower.allFinite());
}

TEST_F(WorkspaceTest, KeepingTooManyPointsIsRefusedBeforeAllocating) {
  const Chain chain(planar_, "tip");
  WorkspaceOptions options;
  options.samples = kMaxKeptWorkspacePoints + 1;
  try {
    sample_workspace(chain, options);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at most 33554432 points"), std::string::npos) << e.what();
  }
  // without the points the same count is only a matter of time: stop it at once
  options.keep_points = false;
  options.stop = [] { return true; };
  EXPECT_EQ(sample_workspace(chain, options).status, SamplingStatus::interrupted);
}

}  // namespace
}  // namespace mjarm
