// Issue 29's numbers and bounds, at the command line: joint values outside their range are
// refused (or, asked for, flagged) by every command that takes them; a profile that breaks its
// limits fails `traj`; a model beyond the element bound is refused before MuJoCo compiles it,
// with one option to raise the bound on every command that loads a model; `run plan` without a
// ROBOT says so; numbers in messages are written in their shortest form.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::CliRun;
using mjarm::test::expect_error;
using mjarm::test::run_cli;
using mjarm::test::run_json;
using mjarm::test::scratch;
using nlohmann::json;

fs::path write_bounds_file(const std::string& name, const std::string& text) {
  const fs::path path = scratch() / name;
  std::ofstream(path) << text;
  return path;
}

/// An MJCF of one body holding @p geoms spheres.
std::string many_geoms(int geoms) {
  std::string xml = "<mujoco model=\"many\">\n  <worldbody>\n    <body name=\"b\">\n";
  for (int i = 0; i < geoms; ++i)
    xml += "      <geom type=\"sphere\" size=\"0.01\" pos=\"0 0 " + std::to_string(0.02 * i) +
           "\"/>\n";
  return xml + "      <joint name=\"j\" axis=\"0 0 1\"/>\n      <site name=\"tip\"/>\n    "
               "</body>\n  </worldbody>\n</mujoco>\n";
}

// the issue's probe: joint1 = 10 rad is beyond its range [-2.8973, 2.8973]
const std::vector<std::string> kOutsideQ{"10", "0", "0", "-1", "0", "1", "0"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(CliBounds, JointValuesOutsideTheirRangeAreRefusedByEveryCommand) {
  const std::string named = "--q: joint 'joint1' = 10 rad, outside its range [-2.8973, 2.8973] rad";
  expect_error(with({"singularities", "panda", "--samples", "0", "--q"}, kOutsideQ), 2, named);
  expect_error(with({"fk", "panda", "--q"}, kOutsideQ), 2, named);
  expect_error(with({"fk", "panda", "--q"}, kOutsideQ), 2, "pass --allow-outside-range");
  expect_error(with({"ik", "panda", "--pos", "0.5", "0.1", "0.4", "--from"}, kOutsideQ), 2,
               "--from: joint 'joint1' = 10 rad, outside its range");
  const fs::path waypoints =
      write_bounds_file("range_wp.json", R"({"waypoints": [{"position": [0.45, 0.0, 0.5]}]})");
  expect_error(with({"plan", "panda", "--waypoints", waypoints.string(), "--q"}, kOutsideQ), 2,
               named);
  expect_error(with({"plan", "panda", "--waypoints", waypoints.string(), "--q"}, kOutsideQ), 2,
               "(--q takes radians: 10° would be 0.1745 rad); a plan starts inside the joint ranges");
  expect_error(
      with({"run", "plan", "panda", "--waypoints", waypoints.string(), "--q"}, kOutsideQ), 2,
      named);
  // `render --q` takes the same check (before the renderer starts)
  expect_error(with({"render", "panda", "--out", (scratch() / "range.png").string(), "--q"},
                    kOutsideQ),
               2, named);
  // a slide joint names its unit; a value in degrees is pointed out
  expect_error({"fk", "panda", "--q", "90", "0", "0", "-1", "0", "1", "0"}, 2,
               "(--q takes radians: 90° would be 1.5708 rad)");
}

TEST(CliBounds, AllowedValuesOutsideTheRangeAreFlaggedEverywhere) {
  const CliRun fk = run_cli(with({"fk", "panda", "--allow-outside-range", "--json", "--q"}, kOutsideQ));
  EXPECT_EQ(fk.exit_code, 0) << fk.err;
  EXPECT_FALSE(json::parse(fk.out)["within_limits"].get<bool>());
  EXPECT_NE(fk.err.find("mjarm: warning: --q: joint 'joint1' = 10 rad, outside"), std::string::npos)
      << fk.err;

  const CliRun sing = run_cli(with(
      {"singularities", "panda", "--samples", "0", "--allow-outside-range", "--json", "--q"},
      kOutsideQ));
  ASSERT_EQ(sing.exit_code, 0) << sing.err;
  const json entry = json::parse(sing.out)["configurations"].back();
  EXPECT_EQ(entry["name"], "--q (outside the joint ranges)");
  EXPECT_FALSE(entry["within_limits"].get<bool>());
  EXPECT_NE(sing.err.find("mjarm: warning: --q: joint 'joint1'"), std::string::npos) << sing.err;

  const CliRun ik = run_cli(with({"ik", "panda", "--pos", "0.5", "0.1", "0.4",
                                  "--allow-outside-range", "--json", "--from"},
                                 kOutsideQ));
  ASSERT_EQ(ik.exit_code, 0) << ik.err;
  const json solved = json::parse(ik.out);
  EXPECT_EQ(solved["start"], "--from (outside the joint ranges)");
  ASSERT_EQ(solved["start_outside_range"].size(), 1u);
  // inside the ranges: nothing said
  const CliRun inside = run_cli({"fk", "panda", "--q", "0", "0", "0", "-1", "0", "1", "0"});
  EXPECT_EQ(inside.exit_code, 0);
  EXPECT_EQ(inside.err, "");
}

TEST(CliBounds, AProfileBeyondItsLimitsFailsUnlessAllowed) {
  const fs::path csv = scratch() / "violating.csv";
  fs::remove(csv);
  const CliRun run =
      run_cli({"traj", "quintic", "--start", "0", "--target", "1", "--duration", "0.1", "--out",
               csv.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.out.find("within limits  NO"), std::string::npos) << run.out;  // the report
  // 15/8 m / 0.1 s and 10/√3 m / (0.1 s)², each in its shortest round-trip form
  EXPECT_NE(run.err.find("the profile breaks its limits (axis 0: peak |v| 18.7"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find(" > v max 0.18; axis 0: peak |a| 577.35"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("no CSV or plot was written; pass --allow-violation"), std::string::npos);
  EXPECT_FALSE(fs::exists(csv));
  for (const char* kind : {"smoothstep", "smootherstep"})
    EXPECT_EQ(
        run_cli({"traj", kind, "--start", "0", "--target", "1", "--duration", "0.1"}).exit_code, 1);
  // the same with JSON: the document is printed, then the error
  const CliRun js = run_cli(
      {"traj", "quintic", "--start", "0", "--target", "1", "--duration", "0.1", "--json"});
  EXPECT_EQ(js.exit_code, 1);
  EXPECT_EQ(json::parse(js.out)["violations"].size(), 2u);
  // accepted: exit 0, the CSV written
  const CliRun allowed =
      run_cli({"traj", "quintic", "--start", "0", "--target", "1", "--duration", "0.1",
               "--allow-violation", "--out", csv.string()});
  EXPECT_EQ(allowed.exit_code, 0) << allowed.err;
  EXPECT_TRUE(fs::exists(csv));
}

TEST(CliBounds, ModelsBeyondTheElementBoundAreRefusedBeforeCompiling) {
  const fs::path big = write_bounds_file("many.xml", many_geoms(20001));
  expect_error({"info", big.string()}, 1,
               "model '" + big.string() + "' has 20005 elements (20001 geom, 1 body, 1 joint)");
  expect_error({"info", big.string()}, 1, "raise the bound with --max-model-elements N");
  // <replicate> copies count: 9 lines that would compile 10⁶ bodies
  const fs::path replicated = write_bounds_file("replicate.xml", R"(<mujoco>
  <worldbody>
    <replicate count="1000" offset="0.01 0 0">
      <replicate count="1000" offset="0 0.01 0">
        <body><joint axis="0 0 1"/><geom size="0.001"/></body>
      </replicate>
    </replicate>
  </worldbody>
</mujoco>)");
  expect_error({"info", replicated.string()}, 1, "3001002 elements (1000000 body");
  // the bound raised on the command line, and lowered
  const fs::path small = write_bounds_file("small.xml", many_geoms(30));
  EXPECT_EQ(run_cli({"info", small.string()}).exit_code, 0);
  expect_error({"info", small.string(), "--max-model-elements", "10"}, 1,
               "34 elements (30 geom, 1 body, 1 joint), more than the 10 a model may have");
  expect_error({"fk", small.string(), "--max-model-elements", "10"}, 1, "more than the 10");
  expect_error({"info", small.string(), "--max-model-elements", "0"}, 2,
               "--max-model-elements: '0' is not a whole number from 1 to 100000000");
  // a scene file's own entries count too
  std::string scene = "objects:\n";
  for (int i = 0; i < 12; ++i)
    scene += "  - {name: o" + std::to_string(i) + ", size: [0.01, 0.01, 0.01], pos: [0, 0, 0.1]}\n";
  expect_error({"info", write_bounds_file("crowd.yaml", scene).string(), "--max-model-elements", "10"},
               1, "scene file '");
}

TEST(CliBounds, EveryCommandThatLoadsAModelTakesTheElementBound) {
  for (const std::vector<std::string>& command : {std::vector<std::string>{"info"},
                                                  {"fk"},
                                                  {"workspace"},
                                                  {"singularities"},
                                                  {"ik"},
                                                  {"render"},
                                                  {"view"},
                                                  {"replay"},
                                                  {"bimanual"},
                                                  {"run", "shelf-pick"},
                                                  {"run", "pick-place"},
                                                  {"run", "docking"},
                                                  {"run", "plan"},
                                                  {"sweep", "run"},
                                                  {"plan"},
                                                  {"demo"},
                                                  {"env", "list"},
                                                  {"env", "run"},
                                                  {"bench", "ik"},
                                                  {"bench", "control"},
                                                  {"bench", "env"},
                                                  {"bench", "plan"},
                                                  {"bench", "diffik"},
                                                  {"bench", "analytic-ik"}}) {
    const CliRun help = run_cli(with(command, {"--help"}));
    EXPECT_EQ(help.exit_code, 0) << command.front();
    EXPECT_NE(help.out.find("--max-model-elements"), std::string::npos) << command.front();
  }
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"traj"}, {"plot"}, {"models"}, {"bench", "otg"}}) {
    const CliRun help = run_cli(with(command, {"--help"}));
    EXPECT_EQ(help.out.find("--max-model-elements"), std::string::npos) << command.front();
  }
}

TEST(CliBounds, RunPlanWithoutARobotSaysSo) {
  const fs::path waypoints =
      write_bounds_file("plan_wp.json", R"({"waypoints": [{"position": [0.45, 0.0, 0.5]}]})");
  expect_error({"run", "plan", "--waypoints", waypoints.string()}, 2,
               "run plan needs a ROBOT (planar2 | panda): mjarm run plan ROBOT --waypoints FILE");
  expect_error({"run", "plan", "pandaa", "--waypoints", waypoints.string()}, 2,
               "run plan: unknown robot 'pandaa'; robots: planar2, panda");
}

TEST(CliBounds, NanInAModelIsAnErrorNamingElementAndAttribute) {
  // issue 29, item 2: MuJoCo 2.2.2 zeroed pos="nan 0 0.3" and fk was silently wrong; MuJoCo
  // 4.0.1 keeps the NaN, warns, and the load check refuses it
  const fs::path nan = write_bounds_file("nan.xml", R"(<mujoco model="nanarm">
  <worldbody>
    <body name="b1" pos="0 0 0.1">
      <joint name="j1" axis="0 0 1"/>
      <geom type="capsule" size="0.02" fromto="0 0 0 0 0 0.3"/>
      <body name="b2" pos="nan 0 0.3">
        <joint name="j2" axis="0 1 0"/>
        <geom type="sphere" size="0.02"/>
        <site name="tip"/>
      </body>
    </body>
  </worldbody>
</mujoco>)");
  const CliRun run = run_cli({"fk", nan.string(), "--q", "0", "0"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("mjarm: error: model '" + nan.string() +
                         "' has a non-finite number: body 'b2', attribute pos = nan 0 0.3"),
            std::string::npos)
      << run.err;
  EXPECT_TRUE(run.out.empty());
}

TEST(CliBounds, HugeNumbersInMessagesAreShort) {
  // a scene object of 1e308 kg: refused with its line, the number in its shortest form
  const fs::path heavy = write_bounds_file(
      "heavy.yaml",
      "objects:\n  - {name: cube, size: [0.02, 0.02, 0.02], mass: 1e308, pos: [0.5, 0, 0.1]}\n");
  expect_error({"info", heavy.string()}, 1,
               "heavy.yaml:2: object 'cube': box object 'cube' mass holds 1e+308, beyond 1e+10");
  const fs::path far = write_bounds_file(
      "far.yaml", "objects:\n  - {name: cube, size: [0.02, 0.02, 0.02], pos: [1e300, 0, 0.1]}\n");
  expect_error({"info", far.string()}, 1, "pos holds 1e+300, beyond 1e+10");
  const CliRun negative = run_cli({"info", write_bounds_file("neg.yaml",
                                                             "objects:\n  - {name: c, size: "
                                                             "[0.02, 0.02, 0.02], mass: -1e9}\n")
                                               .string()});
  EXPECT_NE(negative.err.find("mass must be positive [kg], got -1e+09"), std::string::npos)
      << negative.err;
}

}  // namespace
