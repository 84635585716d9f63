// Standard output that cannot be written (issue 29's bad-input matrix, "every command: standard
// output"): a command whose result does not reach stdout must not exit 0. app/main.cpp flushes
// stdout at the end and fails with "cannot write to standard output" (exit 1); `--help` and
// `--version` take the same check. A pipe closed by its reader ends the command with SIGPIPE,
// or, with SIGPIPE ignored, with that same error.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::scratch;
using mjarm::test::slurp;

/// How a run whose stdout went to a full device or a closed pipe ended.
struct StdoutOutcome {
  int exit_code = -1;
  int signal = 0;
  std::string err;
};

/// Runs the CLI in @p cwd with stdout on /dev/full (@p pipe_fd < 0) or on @p pipe_fd.
StdoutOutcome run_with_stdout(const std::vector<std::string>& args, const fs::path& cwd,
                              int pipe_fd = -1) {
  const fs::path err = scratch() / "stdout_test_stderr.txt";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (pipe_fd < 0)
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/full", O_WRONLY, 0);
  else
    posix_spawn_file_actions_adddup2(&actions, pipe_fd, STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  std::vector<std::string> all{MJARM_CLI};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  StdoutOutcome outcome;
  const int spawned = posix_spawn(&pid, MJARM_CLI, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    ADD_FAILURE() << "cannot start " << MJARM_CLI;
    return outcome;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  outcome.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  outcome.err = slurp(err);
  return outcome;
}

TEST(StandardOutput, EveryCommandFailsWhenStdoutIsAFullDevice) {
  const fs::path cwd = scratch() / "stdout_full";
  fs::create_directories(cwd);
  std::ofstream(cwd / "five.json")
      << R"({"waypoints": [{"position": [0.45, 0.0, 0.50]}, {"position": [0.45, 0.20, 0.40]},
  {"position": [0.35, 0.25, 0.35]}, {"position": [0.30, 0.10, 0.45]},
  {"position": [0.40, -0.15, 0.50]}]})";
  // one of each kind of report: tables, JSON, help, a report after files are written
  const std::vector<std::vector<std::string>> commands{
      {"models"},
      {"info", "planar2"},
      {"fk", "planar2", "--q", "0", "0"},
      {"fk", "planar2", "--q", "0", "0", "--json"},
      {"ik", "panda", "--pos", "0.5", "0.1", "0.4"},
      {"workspace", "planar2", "--samples", "100"},
      {"singularities", "planar2", "--samples", "10"},
      {"traj", "quintic", "--start", "0", "--target", "1", "--out", "traj.csv"},
      {"plan", "panda_torque", "--waypoints", "five.json"},
      {"run", "plan", "panda", "--waypoints", "five.json"},
      {"env", "list"},
      {"env", "run", "reach", "--episodes", "1", "--time-limit", "0.1"},
      {"bench", "otg", "--cases", "10", "--reference-cases", "0"},
      {"bench", "plan", "--plans", "1"},
      {"render", "planar2", "--size", "64x48", "--out", "still.png"},
      {"bimanual", "--json"},
      {"--help"},
      {"fk", "--help"},
      {"--version"}};
  for (const auto& args : commands) {
    const StdoutOutcome run = run_with_stdout(args, cwd);
    EXPECT_EQ(run.signal, 0) << args[0];
    EXPECT_EQ(run.exit_code, 1) << args[0] << " " << args.back() << ": " << run.err;
    EXPECT_NE(run.err.find("mjarm: error: cannot write to standard output"), std::string::npos)
        << args[0] << ": " << run.err;
  }
}

TEST(StandardOutput, APipeClosedByItsReaderIsNotASuccess) {
  // a JSON document larger than a pipe's buffer (about 2 500 samples) and a table
  const std::vector<std::vector<std::string>> commands{
      {"traj", "quintic", "--start", "0", "--target", "1", "--json"},
      {"workspace", "planar2", "--samples", "100"}};
  for (const bool ignored : {false, true}) {
    // the child inherits an ignored SIGPIPE: its writes then fail with EPIPE instead
    struct sigaction keep {};
    struct sigaction ignore {};
    ignore.sa_handler = ignored ? SIG_IGN : SIG_DFL;
    sigemptyset(&ignore.sa_mask);
    sigaction(SIGPIPE, &ignore, &keep);
    for (const auto& args : commands) {
      int fds[2];
      ASSERT_EQ(pipe(fds), 0);
      close(fds[0]);  // the reader is gone before the first byte
      const StdoutOutcome run = run_with_stdout(args, scratch(), fds[1]);
      close(fds[1]);
      if (ignored) {
        EXPECT_EQ(run.exit_code, 1) << args[0] << ": " << run.err;
        EXPECT_NE(run.err.find("mjarm: error: cannot write to standard output"), std::string::npos)
            << run.err;
      } else {
        EXPECT_EQ(run.signal, SIGPIPE) << args[0] << ": exit " << run.exit_code << " " << run.err;
      }
    }
    sigaction(SIGPIPE, &keep, nullptr);
  }
}

}  // namespace
