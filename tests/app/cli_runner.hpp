#pragma once
/// @file
/// Runs the built `mjarm` executable for the app tests: no shell, stdout and stderr captured
/// through files in a scratch directory of the test process.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/files.hpp"

extern char** environ;

namespace mjarm::test {

/// What one run of the CLI did.
struct CliRun {
  int exit_code = -1;
  bool signaled = false;
  std::string out;
  std::string err;
};

/// Runs the CLI with @p args in directory @p cwd (default: the scratch directory).
inline CliRun run_cli(const std::vector<std::string>& args,
                      const std::filesystem::path& cwd = scratch()) {
  const std::filesystem::path out = scratch() / "stdout.txt";
  const std::filesystem::path err = scratch() / "stderr.txt";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  std::vector<std::string> all{MJARM_CLI};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  CliRun run;
  const int spawned = posix_spawn(&pid, MJARM_CLI, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    ADD_FAILURE() << "cannot start " << MJARM_CLI;
    return run;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  run.signaled = WIFSIGNALED(status);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = slurp(out);
  run.err = slurp(err);
  return run;
}

/// Runs the CLI and expects exit 0 with one JSON document on stdout.
inline nlohmann::json run_json(const std::vector<std::string>& args) {
  const CliRun run = run_cli(args);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(nlohmann::json::accept(run.out)) << run.out;
  return nlohmann::json::accept(run.out) ? nlohmann::json::parse(run.out) : nlohmann::json();
}

/// Expects a clean failure: the exit code, one "mjarm: error:" message containing @p needle, no
/// output on stdout, no crash.
inline void expect_error(const std::vector<std::string>& args, int code,
                         const std::string& needle) {
  const CliRun run = run_cli(args);
  EXPECT_FALSE(run.signaled);
  EXPECT_EQ(run.exit_code, code) << run.err;
  EXPECT_EQ(run.err.rfind("mjarm: error: ", 0), 0u) << run.err;
  EXPECT_NE(run.err.find(needle), std::string::npos) << "'" << needle << "' not in: " << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
}

}  // namespace mjarm::test
