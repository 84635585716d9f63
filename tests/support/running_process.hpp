#pragma once
/// @file
/// A program run in the background by a test, to be signalled while it works: started without a
/// shell, stdout and stderr captured through files, waited for with a deadline (a regression
/// that hangs fails the test instead of hanging it), and killed and reaped on destruction
/// whatever the outcome.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "support/files.hpp"

extern char** environ;

namespace mjarm::test {

class RunningProcess {
 public:
  /// Starts @p argv (argv[0] a path) in @p cwd, with the test's environment plus @p env
  /// ("NAME=value" entries replace the test's own).
  RunningProcess(std::vector<std::string> argv, const std::filesystem::path& cwd,
                 const std::vector<std::string>& env = {}) {
    static int counter = 0;
    const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(++counter);
    out_path_ = scratch() / ("running_out_" + tag);
    err_path_ = scratch() / ("running_err_" + tag);
    std::vector<std::string> environment = env;
    for (char** e = environ; *e != nullptr; ++e) {
      const std::string entry = *e;
      const std::string name = entry.substr(0, entry.find('='));
      bool replaced = false;
      for (const std::string& mine : env) replaced = replaced || mine.rfind(name + "=", 0) == 0;
      if (!replaced) environment.push_back(entry);
    }
    std::vector<char*> args, envp;
    for (auto& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    for (auto& e : environment) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
    if (posix_spawn(&pid_, argv[0].c_str(), &actions, nullptr, args.data(), envp.data()) != 0)
      pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~RunningProcess() {
    if (running()) {
      ::kill(pid_, SIGKILL);
      int status = 0;
      while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
    }
  }
  RunningProcess(const RunningProcess&) = delete;
  RunningProcess& operator=(const RunningProcess&) = delete;

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  bool running() const { return pid_ > 0 && !ended_; }
  void signal(int number) const {
    if (running()) ::kill(pid_, number);
  }

  /// Waits up to @p seconds for the program to end; false when it is still running.
  bool wait(double seconds) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(int(seconds * 1000));
    while (running()) {
      int status = 0;
      const pid_t done = ::waitpid(pid_, &status, WNOHANG);
      if (done == pid_) {
        ended_ = true;
        signaled_ = WIFSIGNALED(status);
        exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        break;
      }
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return ended_;
  }

  int exit_code() const { return exit_code_; }
  bool signaled() const { return signaled_; }
  std::string out() const { return slurp(out_path_); }
  std::string err() const { return slurp(err_path_); }

 private:
  pid_t pid_ = -1;
  bool ended_ = false;
  bool signaled_ = false;
  int exit_code_ = -1;
  std::filesystem::path out_path_, err_path_;
};

/// Waits up to @p seconds for @p condition to hold; whether it did.
template <typename Condition>
bool eventually(Condition condition, double seconds) {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(int(seconds * 1000));
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

/// True while process @p pid exists and is not a zombie (reaped or not).
inline bool process_alive(pid_t pid) {
  const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
  if (stat.empty()) return false;
  const std::size_t close = stat.rfind(')');
  return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z';
}

/// True once process @p pid catches signal @p number (its handler is installed: SigCgt in
/// /proc/PID/status), so that a test signals it at a known point instead of after a guessed delay.
inline bool catches_signal(pid_t pid, int number) {
  const std::string status = slurp("/proc/" + std::to_string(pid) + "/status");
  const std::size_t at = status.find("SigCgt:");
  if (at == std::string::npos) return false;
  const unsigned long long mask = std::strtoull(status.c_str() + at + 7, nullptr, 16);
  return (mask >> (number - 1) & 1ULL) != 0;
}

}  // namespace mjarm::test
