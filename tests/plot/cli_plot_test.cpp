// `mjarm plot` through the built executable: paths and --json on success, exit codes and
// messages for bad input.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <vector>

#include "plot/plot_test_support.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs `env ENV mjarm ARGS` through the shell (the arguments are plain temporary paths).
CliResult run_cli(const std::string& args, const test::TempDir& dir, const std::string& env = "") {
  const fs::path out = dir.path() / "stdout.txt", err = dir.path() / "stderr.txt";
  const std::string command = (env.empty() ? "" : "env " + env + " ") + std::string(MJARM_CLI) +
                              " " + args + " > '" + out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = test::read_text(out);
  r.err = test::read_text(err);
  return r;
}

TEST(PlotCli, PrintsThePngPathsAndJson) {
  test::TempDir dir("plot-cli");
  const fs::path rec = dir.path() / "rec";
  test::record_press(rec);
  const CliResult text = run_cli("plot " + rec.string(), dir);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find((rec / "plots" / "tracking_error.png").string() + "\n"),
            std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("phases.png"), std::string::npos) << text.out;

  const CliResult json = run_cli("plot " + rec.string() + " --out " +
                                     (dir.path() / "figs").string() + " --size 640x360 --json",
                                 dir);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json doc = nlohmann::json::parse(json.out);
  ASSERT_EQ(doc["plots"].size(), 4u);
  EXPECT_EQ(doc["size"]["width"], 640);
  for (const auto& p : doc["plots"]) {
    const test::PixelStats s = test::pixel_stats(p["path"].get<std::string>());
    EXPECT_EQ(s.width, 640);
    EXPECT_EQ(s.height, 360);
    EXPECT_GT(s.variance, 300.0) << p["name"];
    EXPECT_FALSE(p["series"].empty()) << p["name"];
    EXPECT_FALSE(p["title"].get<std::string>().empty());
  }
  EXPECT_EQ(doc["plots"][1]["name"], "joint_torques");
}

TEST(PlotCli, BadInputFailsWithAMessage) {
  test::TempDir dir("plot-cli-bad");
  const CliResult missing = run_cli("plot " + (dir.path() / "nothing").string(), dir);
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("does not exist"), std::string::npos) << missing.err;

  const CliResult size = run_cli("plot " + dir.path().string() + " --size 12", dir);
  EXPECT_EQ(size.exit_code, 2);
  EXPECT_NE(size.err.find("WIDTHxHEIGHT"), std::string::npos) << size.err;

  const CliResult none = run_cli("plot", dir);
  EXPECT_EQ(none.exit_code, 2);

  // gnuplot not on PATH: the Debian package is named
  const fs::path rec = dir.path() / "rec";
  test::record_press(rec);
  const CliResult no_gnuplot = run_cli("plot " + rec.string(), dir, "PATH=/nonexistent-bin");
  EXPECT_EQ(no_gnuplot.exit_code, 1);
  EXPECT_NE(no_gnuplot.err.find("gnuplot-nox"), std::string::npos) << no_gnuplot.err;

  test::write_file(dir.path() / "a-file", "x");
  const CliResult unwritable =
      run_cli("plot " + rec.string() + " --out " + (dir.path() / "a-file" / "p").string(), dir);
  // refused before any plotting, as a usage error naming what is in the way
  EXPECT_EQ(unwritable.exit_code, 2);
  EXPECT_NE(unwritable.err.find("a-file' is not a folder"), std::string::npos) << unwritable.err;

  const CliResult help = run_cli("plot --help", dir);
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("gnuplot-nox"), std::string::npos);
}

// `mjarm plot DIR` run without a shell: argv as given, in working folder @p cwd
int run_cli_argv(std::vector<std::string> args, const fs::path& cwd) {
  std::vector<char*> argv{const_cast<char*>(MJARM_CLI)};
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, MJARM_CLI, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// issue 16, item 3: a folder name with a newline and a gnuplot command after it ran the command
TEST(PlotCli, AFolderNameIsNeverACommand) {
  test::TempDir dir("plot-cli-injection");
  const fs::path rec = dir.path() / "rec\nsystem \"touch PWNED\"\n# '`touch PWNED2`$(touch PWNED3)";
  test::record_press(rec);
  EXPECT_EQ(run_cli_argv({"plot", rec.string()}, dir.path()), 0);
  EXPECT_FALSE(fs::exists(dir.path() / "PWNED"));
  EXPECT_FALSE(fs::exists(dir.path() / "PWNED2"));
  EXPECT_FALSE(fs::exists(dir.path() / "PWNED3"));
  EXPECT_GT(test::pixel_stats(rec / "plots" / "phases.png").variance, 300.0);
}

}  // namespace
}  // namespace mjarm
