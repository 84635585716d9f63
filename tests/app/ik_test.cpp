// Drives `mjarm ik`: reachable position targets solve from the default start (the home keyframe,
// else the middle of the ranges) with global restarts when the local solve ends not_converged;
// the start and the restarts are reported; --trace; --timeout-ms is bounded.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "support/random_configurations.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::expect_error;
using mjarm::test::run_cli;
using nlohmann::json;

/// A number as the CLI reads it back bit for bit.
std::string exact(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

/// `mjarm ik MODEL [--site SITE] --pos p --json` plus @p extra.
CliRun run_ik(const std::string& model, const std::string& site, const Eigen::Vector3d& p,
              const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"ik", model};
  if (!site.empty()) args.insert(args.end(), {"--site", site});
  args.insert(args.end(), {"--pos", exact(p.x()), exact(p.y()), exact(p.z()), "--json"});
  args.insert(args.end(), extra.begin(), extra.end());
  return run_cli(args);
}

/// The q of a JSON answer as a vector.
Eigen::VectorXd answer_q(const json& doc) {
  Eigen::VectorXd q(static_cast<Eigen::Index>(doc["q"].size()));
  for (std::size_t i = 0; i < doc["q"].size(); ++i)
    q[static_cast<Eigen::Index>(i)] = doc["q"][i].get<double>();
  return q;
}

/// The default position tolerance of the dls solver [m].
constexpr double kPositionTolerance = 1e-4;

TEST(IkCli, SeededReachableTargetsSolveFromTheDefaultStart) {
  // targets made by forward kinematics of random configurations inside the limits; the full
  // count is `scripts/ik_reachable_check.py --trials 20` (docs/ik.md)
  struct Case {
    const char* model;
    const char* site;  // "" = the model's only site
  };
  for (const Case c : {Case{"panda", ""}, Case{"arm6", "grip"}}) {
    const mjarm::Robot robot = mjarm::Robot::bundled(c.model);
    const mjarm::Chain chain(robot, *c.site ? c.site : "attachment_site");
    mjarm::ChainKinematics fk(chain);
    std::mt19937_64 rng(16);
    for (int t = 0; t < 6; ++t) {
      const Eigen::Vector3d p = fk.update(mjarm::test::random_q(chain, rng)).p;
      const CliRun run = run_ik(c.model, c.site, p);
      ASSERT_EQ(run.exit_code, 0) << c.model << " target " << t << ": " << run.err << run.out;
      const json doc = json::parse(run.out);
      EXPECT_EQ(doc["start"], "keyframe 'home' (default)");
      EXPECT_EQ(doc["status"], "converged");
      // judged by the library's own forward kinematics, not by the command's word
      const Eigen::VectorXd q = answer_q(doc);
      EXPECT_TRUE(chain.within_limits(q)) << c.model << " target " << t;
      EXPECT_LE((fk.update(q).p - p).norm(), kPositionTolerance) << c.model << " target " << t;
    }
  }
}

TEST(IkCli, TheIssuesPandaTargetSolvesAndSaysWhereItStarted) {
  // from qpos0 (outside the joint-4 and joint-6 limits) this ended not_converged, 0.09 m away
  const CliRun run = run_cli({"ik", "panda", "--pos", "0.5", "0.1", "0.4"});
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("keyframe 'home' (default)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("converged"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("restarts            not needed"), std::string::npos) << run.out;
  // an explicit start is still honoured
  const json doc = json::parse(run_ik("panda", "", {0.5, 0.1, 0.4}, {"--key", "home"}).out);
  EXPECT_EQ(doc["start"], "keyframe 'home'");
}

TEST(IkCli, ALocalMinimumAtTheLimitsFallsBackToRestarts) {
  // arm6 from home leaning forward, a target behind its base: dls ends with joint 2 and joint 5
  // on their limits 16 mm short; the global restarts reach it
  const Eigen::Vector3d behind(-0.2479, -0.0263, 0.9254);
  const CliRun local = run_ik("arm6", "grip", behind, {"--solver", "dls"});
  EXPECT_EQ(local.exit_code, 1);
  const json stuck = json::parse(local.out);
  EXPECT_EQ(stuck["status"], "not_converged");
  EXPECT_GT(stuck["position_error"].get<double>(), 0.01);
  EXPECT_FALSE(stuck["restarts_needed"].get<bool>());
  EXPECT_EQ(stuck["global_attempts"], 0);

  const CliRun fallback = run_ik("arm6", "grip", behind);
  ASSERT_EQ(fallback.exit_code, 0) << fallback.err;
  const json doc = json::parse(fallback.out);
  EXPECT_EQ(doc["status"], "converged");
  EXPECT_TRUE(doc["restarts_needed"].get<bool>());
  EXPECT_GE(doc["global_attempts"].get<int>(), 2);
  EXPECT_GT(doc["iterations"].get<int>(), stuck["iterations"].get<int>());
  const mjarm::Robot robot = mjarm::Robot::bundled("arm6");
  const mjarm::Chain chain(robot, "grip");
  mjarm::ChainKinematics fk(chain);
  EXPECT_LE((fk.update(answer_q(doc)).p - behind).norm(), kPositionTolerance);

  const CliRun text =
      run_cli({"ik", "arm6", "--site", "grip", "--pos", "-0.2479", "-0.0263", "0.9254"});
  EXPECT_NE(text.out.find("needed: dls ended not_converged, global restarts solved it"),
            std::string::npos)
      << text.out;
}

TEST(IkCli, WithoutAHomeKeyframeTheStartIsTheMiddleOfTheRanges) {
  // qpos0 = 0 lies outside both ranges; the middle is (1, 1)
  const std::filesystem::path model = mjarm::test::scratch() / "no_home.xml";
  std::ofstream(model) << R"(<mujoco model="no_home">
  <compiler angle="radian"/>
  <worldbody>
    <body name="l1">
      <joint name="a" type="hinge" axis="0 0 1" range="0.5 1.5" limited="true"/>
      <geom type="capsule" fromto="0 0 0 0.4 0 0" size="0.02"/>
      <body name="l2" pos="0.4 0 0">
        <joint name="b" type="hinge" axis="0 0 1" range="0.5 1.5" limited="true"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <site name="tip" pos="0.3 0 0"/>
      </body>
    </body>
  </worldbody>
</mujoco>)";
  const mjarm::Robot robot = mjarm::Robot::load(model.string());
  const mjarm::Chain chain(robot, "tip");
  mjarm::ChainKinematics fk(chain);
  const Eigen::Vector3d p = fk.update(Eigen::Vector2d(0.7, 1.3)).p;
  const CliRun run = run_ik(model.string(), "", p);
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const json doc = json::parse(run.out);
  EXPECT_EQ(doc["start"], "middle of the joint ranges (default)");
  EXPECT_LE((fk.update(answer_q(doc)).p - p).norm(), kPositionTolerance);
}

TEST(IkCli, TracePrintsTheErrorEveryNIterations) {
  const Eigen::Vector3d p(0.372842, -0.215205, 0.307104);
  const CliRun run = run_ik("panda", "", p, {"--trace", "2"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json doc = json::parse(run.out);
  const json& trace = doc["trace"];
  ASSERT_GE(trace.size(), 2u);
  for (std::size_t i = 0; i < trace.size(); ++i) {
    EXPECT_EQ(trace[i]["iteration"], static_cast<int>(2 * i));
    EXPECT_LE(trace[i]["iteration"].get<int>(), doc["iterations"].get<int>());
  }
  EXPECT_GT(trace.front()["position_error"].get<double>(),
            100.0 * trace.back()["position_error"].get<double>());
  EXPECT_FALSE(json::parse(run_ik("panda", "", p).out).contains("trace"));

  const CliRun text = run_cli({"ik", "panda", "--pos", "0.4", "0.1", "0.5", "--rpy", "3.14159", "0",
                               "0", "--solver", "pose", "--trace", "1"});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("trace (pose, every 1 iteration)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("orientation error [rad]"), std::string::npos) << text.out;

  expect_error({"ik", "panda", "--pos", "0.4", "0.1", "0.5", "--solver", "global", "--trace", "1"},
               2, "--trace follows the local solvers");
  expect_error({"ik", "panda", "--pos", "0.4", "0.1", "0.5", "--trace", "0"}, 2, "--trace");
}

// issue 16, item 6: an error about the start names the option the user typed
TEST(IkCli, AWrongFromCountNamesFrom) {
  const CliRun run = run_cli({"ik", "panda", "--pos", "0.4", "0.1", "0.5", "--from", "0", "0"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("--from"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("--q"), std::string::npos) << run.err;
}

TEST(IkCli, TimeoutIsBoundedWithAClearError) {
  // 1e13 ms overflowed the global solver's deadline: `timeout` after 0 iterations
  for (const char* bad : {"1e13", "1e308", "60001", "0", "-1", "nan", "inf", "abc"}) {
    expect_error(
        {"ik", "panda", "--pos", "0.4", "0", "0.5", "--rpy", "3.14", "0", "0", "--timeout-ms", bad},
        2, "at most 60000");
  }
  const CliRun run = run_cli({"ik", "panda", "--pos", "0.4", "0", "0.5", "--rpy", "3.14159", "0",
                              "0", "--timeout-ms", "60000", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json doc = json::parse(run.out);
  EXPECT_EQ(doc["status"], "converged");
  EXPECT_GT(doc["iterations"].get<int>(), 0);
}

}  // namespace
