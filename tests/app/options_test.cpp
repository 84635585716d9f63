// The command-line rules of app/options: every count and rate option bounded with an error that
// names its range (exit 2), seeds that fit 64 bits, subnormal numbers accepted, mistakes in
// --q / --key / --from as usage errors, output paths checked before the work, `--version`.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
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

/// The longest run of digits in @p text (a bound printed as 1.79769e+308 in full has 309).
std::size_t longest_digit_run(const std::string& text) {
  std::size_t longest = 0, run = 0;
  for (const char c : text) {
    run = std::isdigit(static_cast<unsigned char>(c)) ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return longest;
}

TEST(CliOptions, EveryCountAndRateIsBoundedWithItsRangeNamed) {
  const std::string video = (scratch() / "bounded.mp4").string();
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"singularities", "panda", "--samples", "1e20"},
       "--samples: '1e20' is not a whole number from 0 to 100000000"},
      {{"singularities", "panda", "--samples", "100000000000000000000"}, "from 0 to 100000000"},
      {{"singularities", "panda", "--worst", "99999"}, "--worst: '99999'"},
      {{"workspace", "panda", "--samples", "100000001"}, "from 1 to 100000000"},
      {{"demo", "--samples", "1e9"}, "--samples: '1e9' is not a whole number from 1 to 100000000"},
      {{"view", "--render-hz", "1e6"}, "--render-hz: '1e6' is not a number from 1 to 240"},
      {{"view", "--input-hz", "1e9"}, "--input-hz: '1e9' is not a number from 1 to 1000"},
      {{"view", "--speed", "0"}, "--speed: '0' is not a number from 0.01 to 100"},
      {{"view", "--frames", "1e12"}, "--frames: '1e12' is not a whole number from 0 to 1000000"},
      {{"run", "shelf-pick", "--video", video, "--fps", "1e9"},
       "--fps: '1e9' is not a number from 1 to 240"},
      {{"run", "shelf-pick", "--video", video, "--size", "8000x8000"},
       "between 2x2 and 4096x4096 pixels"},
      {{"run", "shelf-pick", "--settle-time", "1e300"}, "--settle-time: '1e300'"},
      {{"run", "shelf-pick", "--control-period", "5"}, "--control-period: '5'"},
      {{"run", "shelf-pick", "--all", "--seeds", "100000"}, "from 1 to 10000"},
      {{"bench", "control", "panda", "--steps", "1e9"}, "--steps: '1e9'"},
      {{"bench", "control", "panda", "--warmup", "-1"}, "from 0 to 1000000"},
      {{"plot", "rec", "--size", "20000x20000"}, "between 200x150 and 8192x8192 pixels"},
      // the value is checked before it is converted: no 309-digit bound for text
      {{"view", "--render-hz", "abc"}, "--render-hz: 'abc' is not a number from 1 to 240"},
  };
  // the work is estimated before it starts: frames = --fps × --settle-time
  expect_error({"run", "shelf-pick", "--video", video, "--fps", "240", "--settle-time", "60"}, 2,
               "would film up to 14400 frames after the approach; at most 9000");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args[0] + " " + c.args.back());
    expect_error(c.args, 2, c.message);
    EXPECT_LT(longest_digit_run(run_cli(c.args).err), 25u);
  }
  EXPECT_FALSE(fs::exists(video));
}

TEST(CliOptions, SeedsFitSixtyFourBitsAndAreReadInDecimal) {
  expect_error({"workspace", "planar2", "--seed", "18446744073709551616"}, 2,
               "--seed: '18446744073709551616' is too large (at most 18446744073709551615)");
  expect_error({"run", "shelf-pick", "--seed", "99999999999999999999999"}, 2, "is too large");
  const json top = run_json(
      {"workspace", "planar2", "--samples", "10", "--seed", "18446744073709551615", "--json"});
  EXPECT_EQ(top["seed"].get<std::uint64_t>(), std::numeric_limits<std::uint64_t>::max());
  // "010" would be read as octal eight: refused, and so is "0x10"
  expect_error({"workspace", "planar2", "--seed", "010"}, 2,
               "--seed: '010' starts with 0; write the number without leading zeros");
  expect_error({"workspace", "planar2", "--samples", "0x10"}, 2, "'0x10' is not a whole number");
  EXPECT_EQ(run_json({"workspace", "planar2", "--samples", "10", "--seed", "0", "--json"})["seed"],
            0);
}

TEST(CliOptions, SubnormalNumbersAreFinite) {
  const json doc = run_json({"fk", "planar2", "--q", "1e-320", "0", "--json"});
  const double q0 = doc["q"][0].get<double>();
  EXPECT_EQ(std::fpclassify(q0), FP_SUBNORMAL);
  EXPECT_EQ(q0, 1e-320);
  expect_error({"fk", "planar2", "--q", "1e400", "0"}, 2, "'1e400' is not a finite number");
}

TEST(CliOptions, ConfigurationMistakesAreUsageErrors) {
  expect_error({"fk", "panda", "--q", "0", "0"}, 2,
               "--q has 2 values but the chain to 'attachment_site' of model 'panda' has 7");
  expect_error({"fk", "panda", "--key", "hom"}, 2, "--key: keyframe 'hom' not found");
}

TEST(CliOptions, VersionComesFromTheProject) {
  const CliRun run = run_cli({"--version"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out.rfind("mjarm 0.", 0), 0u) << run.out;
  // the MuJoCo it runs on, as the library says
  EXPECT_NE(run.out.find(std::string("MuJoCo ") + mj_versionString()), std::string::npos)
      << run.out;
}

TEST(CliOptions, OutputPathsAreCheckedBeforeTheWork) {
  // a file where a folder should be, a folder where a file should be, /proc, a missing folder
  const fs::path file = scratch() / "options_plain_file";
  std::ofstream(file) << "x";
  const fs::path folder = scratch() / "options_folder";
  fs::create_directories(folder);
  expect_error({"workspace", "planar2", "--out", "/proc/x.csv"}, 2,
               "--out: cannot create '/proc/x.csv'");
  expect_error({"workspace", "planar2", "--out", folder.string()}, 2,
               "is a folder, expected a file name");
  expect_error({"workspace", "planar2", "--out", (file / "x.csv").string()}, 2, "is not a folder");
  expect_error({"workspace", "planar2", "--out", (scratch() / "none" / "x.csv").string()}, 2,
               "does not exist");
  expect_error({"run", "shelf-pick", "--record", "/proc/rec"}, 2,
               "--record: cannot write into '/proc'");
  expect_error({"render", "planar2", "--out", "/proc/x.png"}, 2, "--out: cannot create");
  EXPECT_EQ(mjarm::test::slurp(file), "x");
  // issue 16, item 6's symbolic link loop, on the output side: named for what it is (it was
  // "File exists"), and left as it was
  const fs::path loop = scratch() / "options_loop.csv", other = scratch() / "options_loop2.csv";
  fs::create_symlink(other.filename(), loop);
  fs::create_symlink(loop.filename(), other);
  expect_error({"workspace", "planar2", "--out", loop.string()}, 2,
               "--out: '" + loop.string() + "' is a symbolic link loop");
  expect_error({"run", "shelf-pick", "--record", loop.string()}, 2,
               "--record: '" + loop.string() + "' is a symbolic link loop");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(loop)));
  EXPECT_TRUE(fs::is_empty(folder));  // the probe leaves nothing behind
}

TEST(CliOptions, WorkspaceMemoryAndDiskAreEstimatedBeforeTheWork) {
  // 10^8 points would be 3 GB: refused at once, not after minutes or with std::bad_alloc
  const std::string csv = (scratch() / "big.csv").string();
  expect_error({"workspace", "panda", "--samples", "100000000", "--out", csv}, 2,
               "with --out at most 33554432 samples are allowed");
  expect_error({"workspace", "panda", "--samples", "33554433", "--out", csv}, 2, "MiB of points");
  EXPECT_FALSE(fs::exists(csv));
}

}  // namespace
