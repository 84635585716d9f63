// Drives the built `mjarm` executable: exit codes, error messages on stderr, and JSON output
// cross-checked against the library and against closed-form kinematics of planar2.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::CliRun;
using mjarm::test::expect_error;
using mjarm::test::run_cli;
using mjarm::test::run_json;
using mjarm::test::scratch;
using nlohmann::json;

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path path = scratch() / name;
  std::ofstream(path) << text;
  return path;
}

// planar2 from its model file: shoulder 1 m above the floor, links 0.4 m and 0.35 m along +x at
// q = 0, both hinges about +y (a positive angle turns the link from +x towards −z)
constexpr double kL1 = 0.4, kL2 = 0.35, kShoulderHeight = 1.0;
Eigen::Vector3d planar2_tip(double q1, double q2) {
  return {kL1 * std::cos(q1) + kL2 * std::cos(q1 + q2), 0.0,
          kShoulderHeight - kL1 * std::sin(q1) - kL2 * std::sin(q1 + q2)};
}

Eigen::VectorXd to_vector(const json& array) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(array.size()));
  for (std::size_t i = 0; i < array.size(); ++i)
    v[static_cast<Eigen::Index>(i)] = array[i].get<double>();
  return v;
}

// `mjarm COMMAND …` registers that command alone (app/main.cpp): each command that `mjarm --help`
// lists, and that an unknown command's message names, works alone
TEST(Cli, HelpWorksOnEveryCommand) {
  const CliRun all = run_cli({"--help"});
  EXPECT_EQ(all.exit_code, 0);
  EXPECT_NE(all.out.find("Usage"), std::string::npos);
  const CliRun unknown = run_cli({"frobnicate"});
  const std::string listed = "; commands: ";
  const std::size_t at = unknown.err.find(listed);
  ASSERT_NE(at, std::string::npos) << unknown.err;
  std::istringstream names(unknown.err.substr(at + listed.size()));
  std::vector<std::string> commands;
  for (std::string name; names >> name && name != "Run";) {
    if (name.back() == ',') name.pop_back();
    commands.push_back(name);
  }
  EXPECT_EQ(commands.size(), 20u) << unknown.err;
  for (const std::string& command : commands) {
    EXPECT_NE(all.out.find("\n  " + command + " "), std::string::npos) << command;
    const CliRun run = run_cli({command, "--help"});
    EXPECT_EQ(run.exit_code, 0) << command << ": " << run.err;
    EXPECT_NE(run.out.find("Usage: mjarm " + command + " "), std::string::npos) << run.out;
  }
  const CliRun bare = run_cli({});
  EXPECT_EQ(bare.exit_code, 2);
  EXPECT_NE(bare.err.find("Subcommands"), std::string::npos);
}

TEST(Cli, ModelsListsTheBundledModels) {
  const json doc = run_json({"models", "--json"});
  EXPECT_EQ(doc["models"].get<std::vector<std::string>>(), mjarm::Robot::bundled_names());
  const json same = run_json({"info", "--list", "--json"});
  EXPECT_EQ(same, doc);
}

TEST(Cli, AMissingOrEmptyModelsFolderIsAnError) {
  const char* old = std::getenv("MJARM_MODELS");
  const std::string saved = old ? old : "";
  const fs::path empty = scratch() / "empty_models";
  fs::create_directories(empty);
  for (const std::string& folder : {std::string("/nonexistent"), empty.string()}) {
    ::setenv("MJARM_MODELS", folder.c_str(), 1);
    // every command that looks up bundled models names the folder and the variable
    for (const std::vector<std::string>& args :
         std::vector<std::vector<std::string>>{{"models"},
                                               {"models", "--json"},
                                               {"info", "--list"},
                                               {"fk", "panda"},
                                               {"bench", "control", "panda"}}) {
      const CliRun run = run_cli(args);
      EXPECT_EQ(run.exit_code, 1) << args[0] << " " << folder;
      EXPECT_NE(run.err.find("bundled models folder '" + folder + "' (from $MJARM_MODELS)"),
                std::string::npos)
          << run.err;
      EXPECT_TRUE(run.out.empty()) << run.out;
    }
  }
  if (old) {
    ::setenv("MJARM_MODELS", saved.c_str(), 1);
  } else {
    ::unsetenv("MJARM_MODELS");
  }
}

TEST(Cli, InfoJsonMatchesTheLibrary) {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda");
  const json doc = run_json({"info", "panda", "--json"});
  EXPECT_EQ(doc["name"], "panda");
  EXPECT_EQ(doc["nq"], robot.nq());
  EXPECT_EQ(doc["nv"], robot.nv());
  EXPECT_EQ(doc["nu"], robot.nu());
  const auto joints = robot.joints();
  ASSERT_EQ(doc["joints"].size(), joints.size());
  for (std::size_t i = 0; i < joints.size(); ++i) {
    EXPECT_EQ(doc["joints"][i]["name"], joints[i].name);
    EXPECT_EQ(doc["joints"][i]["type"], "hinge");
    EXPECT_EQ(doc["joints"][i]["range"][0].get<double>(), joints[i].lower);
    EXPECT_EQ(doc["joints"][i]["range"][1].get<double>(), joints[i].upper);
  }
  const auto actuators = robot.actuators();
  ASSERT_EQ(doc["actuators"].size(), actuators.size());
  EXPECT_EQ(doc["actuators"][0]["kind"], "position");
  EXPECT_EQ(doc["actuators"][0]["joint"], joints[0].name);
  EXPECT_EQ(doc["actuators"][0]["ctrlrange"][1].get<double>(), actuators[0].ctrl_upper);
  EXPECT_EQ(doc["sites"].get<std::vector<std::string>>(), robot.site_names());
  EXPECT_EQ(doc["keyframes"].get<std::vector<std::string>>(), robot.keyframe_names());
  EXPECT_TRUE(doc["warnings"].empty());
  for (const char* key : {"source", "bodies", "sensors", "cameras"})
    EXPECT_TRUE(doc.contains(key)) << key;

  const CliRun table = run_cli({"info", "panda"});
  EXPECT_EQ(table.exit_code, 0);
  EXPECT_NE(table.out.find("joint4  hinge  -3.0718  -0.0698  rad"), std::string::npos) << table.out;
}

TEST(Cli, InfoLoadsNewerMjcfAsIsAndReportsSensors) {
  const fs::path path = write_file("v3.xml", R"(<mujoco model="v3">
  <option integrator="implicitfast"/>
  <worldbody><body name="b"><joint name="j" axis="0 0 1" range="-1 1"/>
    <geom type="sphere" size="0.1"/><site name="s"/></body></worldbody>
  <sensor><jointpos name="jp" joint="j"/><framepos name="fp" objtype="site" objname="s"/></sensor>
</mujoco>)");
  const json doc = run_json({"info", path.string(), "--json"});
  // MuJoCo loads it as written: nothing rewritten, nothing to warn about
  EXPECT_TRUE(doc["warnings"].empty());
  EXPECT_EQ(doc["integrator"], "implicitfast");
  ASSERT_EQ(doc["sensors"].size(), 2u);
  EXPECT_EQ(doc["sensors"][1]["name"], "fp");
  EXPECT_EQ(doc["sensors"][1]["address"], 1);
  EXPECT_EQ(doc["sensors"][1]["dimension"], 3);
  // MJCF angles default to degrees: the range is reported in radians
  EXPECT_NEAR(doc["joints"][0]["range"][1].get<double>(), std::numbers::pi / 180.0, 1e-15);
}

TEST(Cli, InfoDescribesASceneFile) {
  const fs::path scene = fs::path(MJARM_MODELS_DIR) / "scenes" / "pick_table.yaml";
  const json doc = run_json({"info", scene.string(), "--json"});
  EXPECT_EQ(doc["name"], "pick_table");
  EXPECT_EQ(doc["nq"], 7 + 2 + 7 + 7);
  EXPECT_EQ(doc["nu"], 9);
  EXPECT_EQ(doc["joints"][8]["name"], "panda/hand/finger_right");
  EXPECT_EQ(doc["joints"][9]["type"], "free");
  EXPECT_EQ(doc["sensors"].size(), 4u);
  expect_error(
      {"info", write_file("bad_scene.yaml", "objects:\n  - {name: c, mass: heavy}\n").string()}, 1,
      "bad_scene.yaml:2: key 'mass' in object 'c' expects a number, got 'heavy'");
}

// issue 29, item 1, for MJCF: a misspelt attribute or element is refused by MuJoCo's schema; the
// message names it, the user's file and the line (pinned here: the bad-input matrix's MJCF names)
TEST(Cli, MisspeltMjcfAttributesAndElementsAreRefusedWithTheFileAndLine) {
  const std::string body = R"(<mujoco model="m">
  <worldbody>
    BODY
      <joint type="hinge"/>
      <geom type="sphere" size="0.1"/>
    END
  </worldbody>
</mujoco>
)";
  const auto model = [&](const std::string& name, const std::string& open,
                         const std::string& close) {
    std::string text = body;
    text.replace(text.find("BODY"), 4, open);
    text.replace(text.find("END"), 3, close);
    return write_file(name, text).string();
  };
  const std::string attribute =
      model("nmae.xml", R"(<body nmae="b" pos="0 0 0.1">)", "</body>");
  expect_error({"info", attribute}, 1,
               "Schema violation: unrecognized attribute: 'nmae'\nElement 'body', line 3 of '" +
                   attribute + "'");
  const std::string element = model("bodyy.xml", R"(<bodyy name="b">)", "</bodyy>");
  expect_error({"info", element}, 1,
               "Schema violation: unrecognized element\nElement 'bodyy', line 3 of '" + element +
                   "'");
}

TEST(Cli, FkOfPlanar2MatchesClosedForm) {
  const json zero = run_json({"fk", "planar2", "--site", "tip", "--q", "0", "0", "--json"});
  const Eigen::Vector3d p = to_vector(zero["position"]);
  EXPECT_LT((p - Eigen::Vector3d(kL1 + kL2, 0.0, kShoulderHeight)).norm(), 1e-12) << p.transpose();
  EXPECT_EQ(zero["configuration"], "--q");
  EXPECT_EQ(zero["frame"]["name"], "tip");
  EXPECT_TRUE(zero["within_limits"].get<bool>());
  // values outside the joint range are refused (exit 2), or with --allow-outside-range computed
  // and flagged (issue 29: one rule for every command that takes joint values)
  expect_error({"fk", "planar2", "--q", "2.0", "0"}, 2, "outside its range");
  const json outside =
      run_json({"fk", "planar2", "--q", "2.0", "0", "--allow-outside-range", "--json"});
  EXPECT_FALSE(outside["within_limits"].get<bool>());
  EXPECT_LT((to_vector(outside["position"]) - planar2_tip(2.0, 0.0)).norm(), 1e-12);

  // a general configuration (negative values parse as numbers), with the Jacobian
  const double q1 = 0.3, q2 = -0.7;
  const json doc = run_json({"fk", "planar2", "--q", "0.3", "-0.7", "--jacobian", "--json"});
  EXPECT_LT((to_vector(doc["position"]) - planar2_tip(q1, q2)).norm(), 1e-12);
  // the tip frame is rotated by q1 + q2 about +y
  const Eigen::Vector4d quat = to_vector(doc["quaternion_wxyz"]);
  const double half = 0.5 * (q1 + q2);
  EXPECT_LT((quat - Eigen::Vector4d(std::cos(half), 0, std::sin(half), 0)).norm(), 1e-12)
      << quat.transpose();
  EXPECT_NEAR(doc["rpy"][1].get<double>(), q1 + q2, 1e-12);
  EXPECT_NEAR(doc["rotation"][0][2].get<double>(), std::sin(q1 + q2), 1e-12);
  // Jacobian columns against central differences of the closed form
  const json& J = doc["jacobian"]["data"];
  ASSERT_EQ(J.size(), 6u);
  ASSERT_EQ(J[0].size(), 2u);
  const Eigen::MatrixXd fd = mjarm::finite_difference_jacobian(
      [](const Eigen::VectorXd& q) { return planar2_tip(q[0], q[1]); }, Eigen::Vector2d(q1, q2));
  const Eigen::Vector3d d1 = fd.col(0);
  const Eigen::Vector3d d2 = fd.col(1);
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(J[r][0].get<double>(), d1[r], 1e-8);
    EXPECT_NEAR(J[r][1].get<double>(), d2[r], 1e-8);
  }
  EXPECT_EQ(J[4][0].get<double>(), 1.0);  // ω_y of both hinges
  EXPECT_EQ(J[4][1].get<double>(), 1.0);
}

TEST(Cli, FkAtAKeyframeMatchesTheLibrary) {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda");
  const mjarm::Chain chain(robot, "attachment_site");
  mjarm::ChainKinematics kin(chain);
  const std::vector<double> home = robot.keyframe_qpos("home");
  const mjarm::Pose& X_WE = kin.update(chain.gather(home.data()));

  const json doc = run_json({"fk", "panda", "--key", "home", "--json"});
  EXPECT_EQ(doc["frame"]["name"], "attachment_site");  // the model's only site is the default
  EXPECT_EQ(doc["configuration"], "keyframe 'home'");
  EXPECT_EQ(to_vector(doc["position"]), Eigen::VectorXd(X_WE.p));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(doc["rotation"][r][c].get<double>(), X_WE.R(r, c));
  }
  EXPECT_NEAR(to_vector(doc["quaternion_wxyz"]).norm(), 1.0, 1e-14);

  const CliRun table = run_cli({"fk", "panda", "--key", "home"});
  EXPECT_EQ(table.exit_code, 0);
  EXPECT_NE(table.out.find("position [m]"), std::string::npos);
  EXPECT_TRUE(table.err.empty()) << table.err;
}

TEST(Cli, BadCommandLinesFailCleanly) {
  // a wrong count of --q values is a mistake on the command line: exit 2
  expect_error({"fk", "planar2", "--q", "0", "0", "0"}, 2, "--q has 3 values");
  expect_error({"fk", "planar2", "--q", "0"}, 2, "--q has 1 values");
  expect_error({"singularities", "planar2", "--q", "0"}, 2, "--q has 1 values");
  expect_error({"fk", "planar2", "--q", "0", "nan"}, 2, "'nan' is not a finite number");
  expect_error({"fk", "planar2", "--q", "inf", "0"}, 2, "'inf' is not a finite number");
  expect_error({"fk", "planar2", "--q", "1e999", "0"}, 2, "not a finite number");
  // every --size goes through one parser: the window's too (checked before any window opens)
  expect_error({"view", "panda", "--size", "wide"}, 2, "'wide' is not a size WIDTHxHEIGHT");
  expect_error({"view", "panda", "--size", "0x480"}, 2, "between 1x1 and 7680x4320 pixels");
  expect_error({"fk", "planar2", "--q", "0", "0.5rad"}, 2, "'0.5rad' is not a number");
  expect_error({"fk", "planar2", "--q", "0", "0", "--key", "home"}, 2, "excludes");
  expect_error({"fk", "planar2", "--site", "tpi"}, 1, "tip");
  expect_error({"fk", "planar2", "--key", "hoem"}, 2, "home");
  expect_error({"fk", "dual_arm"}, 2, "left_hand");  // several sites: --site is required
  expect_error({"info", "pandaa"}, 1, "panda");
  expect_error({"info"}, 2, "MODEL is required");
  expect_error({"info", (scratch() / "missing.xml").string()}, 1, "does not exist");
  expect_error({"info", write_file("broken.xml", "<mujoco><worldbody><body>").string()}, 1,
               "malformed XML");
  expect_error({"info", write_file("invalid.xml",
                                   "<mujoco><worldbody><geom type='sphere'/></worldbody></mujoco>")
                            .string()},
               1, "invalid.xml");
  expect_error({"fk", "planar2", "--bogus"}, 2, "--bogus");
  expect_error({"frobnicate"}, 2, "unknown command 'frobnicate'; commands: models, info");
  expect_error({"workspace", "planar2", "--samples", "0"}, 2, "--samples");
  expect_error({"workspace", "planar2", "--out", (scratch() / "no_dir" / "cloud.csv").string()}, 2,
               "cloud.csv");
  expect_error({"singularities", "planar2", "--block", "linear"}, 2, "linear");
  expect_error({"workspace", "planar2", "--seed", "-1"}, 2, "--seed");
  expect_error({"singularities", "planar2", "--samples", "-5"}, 2, "--samples");
}

TEST(Cli, WorkspaceIsSeededAndMatchesTheLibrary) {
  const fs::path csv = scratch() / "cloud.csv";
  const json doc = run_json({"workspace", "planar2", "--samples", "3000", "--seed", "7", "--out",
                             csv.string(), "--json"});
  const mjarm::Robot robot = mjarm::Robot::bundled("planar2");
  const mjarm::Chain chain(robot, "tip");
  const mjarm::WorkspaceResult expected =
      mjarm::sample_workspace(chain, {.samples = 3000, .seed = 7});
  EXPECT_EQ(doc["samples"], 3000);
  EXPECT_EQ(doc["seed"], 7);
  EXPECT_EQ(to_vector(doc["lower"]), Eigen::VectorXd(expected.lower));
  EXPECT_EQ(to_vector(doc["upper"]), Eigen::VectorXd(expected.upper));
  EXPECT_EQ(doc["max_reach_from_base"].get<double>(), expected.max_reach_from_base);
  // the arm cannot reach further than its stretched length, and moves in the x-z plane only
  EXPECT_LE(doc["max_reach_from_base"].get<double>(), kL1 + kL2 + 1e-12);
  EXPECT_EQ(doc["extent"][1].get<double>(), 0.0);
  EXPECT_GT(doc["samples_per_second"].get<double>(), 0.0);
  // CSV: header + one line per sample
  std::ifstream in(csv);
  std::string line;
  int lines = 0;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,z,manipulability");
  while (std::getline(in, line)) ++lines;
  EXPECT_EQ(lines, 3000);

  // same seed, same numbers; no progress noise when stderr is not a terminal
  const CliRun again =
      run_cli({"workspace", "planar2", "--samples", "3000", "--seed", "7", "--json"});
  EXPECT_TRUE(again.err.empty()) << again.err;
  EXPECT_EQ(json::parse(again.out)["upper"], doc["upper"]);
}

TEST(Cli, SingularitiesOfPlanar2FollowTheClosedForm) {
  // position block of a planar 2-link arm: w = l1·l2·|sin q2|, singular when stretched
  const json doc = run_json({"singularities", "planar2", "--block", "position", "--q", "0.3",
                             "-1.0", "--samples", "500", "--seed", "2", "--worst", "3", "--json"});
  EXPECT_EQ(doc["block"], "position");
  const json& configs = doc["configurations"];
  ASSERT_GE(configs.size(), 3u);
  // the report starts at qpos0: planar2 stretched out
  EXPECT_EQ(to_vector(configs[0]["q"]), Eigen::VectorXd::Zero(2));
  EXPECT_EQ(configs[0]["status"], "singular");
  EXPECT_TRUE(configs[0]["condition_number"].is_null());
  const json& given = configs.back();
  EXPECT_EQ(given["name"], "--q");
  EXPECT_NEAR(given["manipulability"].get<double>(), kL1 * kL2 * std::sin(1.0), 1e-12);
  EXPECT_EQ(given["status"], "regular");
  ASSERT_EQ(doc["scan"]["worst"].size(), 3u);
  EXPECT_LE(doc["scan"]["worst"][0]["sigma_min"].get<double>(),
            doc["scan"]["worst"][1]["sigma_min"].get<double>());
  EXPECT_EQ(doc["scan"]["samples"], 500);
  // the kinds: a planar arm has no wrist, elbow or shoulder in this sense
  EXPECT_EQ(configs[0]["kinds"], json::array({"unclassified"}));
  EXPECT_TRUE(configs[0]["below_sigma_min"].get<bool>());
  // stretched, (l1 + l2)·q̇1 + l2·q̇2 = 0 leaves the tip still
  const Eigen::VectorXd lost = to_vector(configs[0]["null_direction"]);
  EXPECT_NEAR(lost[0] / lost[1], -kL2 / (kL1 + kL2), 1e-12);
  EXPECT_EQ(given["kinds"], json::array());
  EXPECT_GE(doc["scan"]["flagged"].get<int>(), doc["scan"]["near_singular"].get<int>());
  const json arm6 = run_json({"singularities", "arm6", "--site", "grip", "--q", "0", "0.2", "1.4",
                              "0", "0", "0", "--samples", "0", "--json"});
  EXPECT_EQ(arm6["configurations"].back()["kinds"], json::array({"wrist"}));
  EXPECT_EQ(arm6["configurations"][0]["kinds"], json::array({"wrist", "elbow", "shoulder"}));
  EXPECT_EQ(arm6["sigma_min_threshold"], 0.01);

  const CliRun table = run_cli({"singularities", "planar2", "--samples", "0"});
  EXPECT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("σmin"), std::string::npos);
  EXPECT_NE(table.out.find("unclassified"), std::string::npos);
  EXPECT_EQ(table.out.find("random scan"), std::string::npos);
}

TEST(Cli, DemoChecksEveryArgumentBeforeTheShelfPick) {
  // each mistake fails at once: no shelf pick, nothing written, nothing on stdout
  const fs::path cwd = scratch() / "demo_checks";
  fs::create_directories(cwd);
  const auto demo_error = [&](const std::vector<std::string>& args, int code,
                              const std::string& needle) {
    const CliRun run = run_cli(args, cwd);
    EXPECT_EQ(run.exit_code, code) << run.err;
    EXPECT_NE(run.err.find(needle), std::string::npos) << needle << " not in: " << run.err;
    EXPECT_TRUE(run.out.empty()) << run.out;
    EXPECT_FALSE(fs::exists(cwd / "out")) << args.back();
  };
  demo_error({"demo", "--model", "pandaa"}, 1, "no bundled model named 'pandaa'");
  demo_error({"demo", "--key", "hom"}, 2, "--key: keyframe 'hom' not found");
  demo_error({"demo", "--model", "dual_arm"}, 2, "choose one with --site");
  demo_error({"demo", "--record", "/proc/demo"}, 2, "--record: cannot write into '/proc'");
  demo_error({"demo", "--video", "/proc/demo.mp4"}, 2, "--video: cannot create '/proc/demo.mp4'");
  // gnuplot missing from PATH: named before the shelf pick, not after it
  const char* path = std::getenv("PATH");
  const std::string saved = path != nullptr ? path : "";
  setenv("PATH", "/nonexistent", 1);
  const CliRun no_gnuplot = run_cli({"demo"}, cwd);
  setenv("PATH", saved.c_str(), 1);
  EXPECT_EQ(no_gnuplot.exit_code, 1) << no_gnuplot.err;
  EXPECT_NE(no_gnuplot.err.find("gnuplot was not found on PATH"), std::string::npos)
      << no_gnuplot.err;
  EXPECT_TRUE(no_gnuplot.out.empty()) << no_gnuplot.out;
  EXPECT_FALSE(fs::exists(cwd / "out"));
}

// the tour after the main job; the job's video and replay page are checked by
// RunCli.DemoRunsTheShelfPickAndRecordsIntoOutDemo, here they are left out (the costly part)
TEST(Cli, DemoRunsTheTour) {
  const json doc = run_json({"demo", "--samples", "2000", "--video", "", "--html", "", "--json"});
  EXPECT_EQ(doc["model"]["name"], "panda");
  EXPECT_EQ(doc["fk"]["configuration"], "keyframe 'home'");
  EXPECT_EQ(doc["workspace"]["samples"], 2000);
  EXPECT_EQ(doc["ik"]["status"], "converged");
  EXPECT_LE(doc["ik"]["position_error"].get<double>(), 1e-5);

  const CliRun text = run_cli({"demo", "--video", "", "--html", ""});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  for (const char* heading : {"== model ==", "== forward kinematics ==", "== workspace ==",
                              "== inverse kinematics round trip =="}) {
    EXPECT_NE(text.out.find(heading), std::string::npos) << heading;
  }
  EXPECT_NE(text.out.find("20000 (seed 1"), std::string::npos);
}

}  // namespace
