#pragma once
/// @file
/// Starts the built `mjarm` in the background for the Ctrl-C tests: SIGINT is sent once the
/// process is past its start-up (it has used some CPU time, or printed a given line), never
/// after a fixed wall-clock delay, so a busy machine does not make the tests flaky.

#include <signal.h>
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/cli_runner.hpp"

namespace mjarm::test {

/// A CLI process started by `start_cli`.
struct StartedCli {
  pid_t pid = -1;
  std::filesystem::path out;
  std::filesystem::path err;
};

/// Starts the CLI with @p args; stdout and stderr go to files named after @p tag.
inline StartedCli start_cli(const std::vector<std::string>& args, const std::string& tag,
                            const std::filesystem::path& cwd = scratch()) {
  StartedCli started;
  started.out = scratch() / (tag + ".out");
  started.err = scratch() / (tag + ".err");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, started.out.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, started.err.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  std::vector<std::string> all{MJARM_CLI};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  if (posix_spawn(&started.pid, MJARM_CLI, &actions, nullptr, argv.data(), environ) != 0) {
    ADD_FAILURE() << "cannot start " << MJARM_CLI;
    started.pid = -1;
  }
  posix_spawn_file_actions_destroy(&actions);
  return started;
}

/// CPU time [s] process @p pid has used (user + system, from /proc/PID/stat); -1 once gone.
inline double cpu_seconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');
  if (close == std::string::npos) return -1.0;
  std::istringstream fields(text.substr(close + 2));
  std::string field;
  long ticks = 0;
  // fields after the name: state (3) … utime (14), stime (15)
  for (int i = 3; i <= 15 && fields >> field; ++i) {
    if (i == 3 && field == "Z") return -1.0;
    if (i >= 14) ticks += std::stol(field);
  }
  return static_cast<double>(ticks) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

/// Waits until @p ready() or the process is gone; gives up after @p limit (a guard against a
/// hang, not a timing check). Returns whether it became ready.
template <typename Ready>
bool wait_until(const StartedCli& cli, Ready ready,
                std::chrono::seconds limit = std::chrono::seconds(300)) {
  const auto give_up = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < give_up) {
    if (ready()) return true;
    if (cpu_seconds(cli.pid) < 0.0) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

/// Sends SIGINT once the process has used @p cpu seconds of CPU (its start-up is behind it).
inline void interrupt_after_cpu(const StartedCli& cli, double cpu) {
  if (wait_until(cli, [&] { return cpu_seconds(cli.pid) >= cpu; })) kill(cli.pid, SIGINT);
}

/// Waits for the process to end and collects what it did.
inline CliRun finish_cli(const StartedCli& cli) {
  CliRun run;
  if (cli.pid < 0) return run;
  int status = 0;
  while (waitpid(cli.pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.signaled = WIFSIGNALED(status);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = slurp(cli.out);
  run.err = slurp(cli.err);
  return run;
}

}  // namespace mjarm::test
