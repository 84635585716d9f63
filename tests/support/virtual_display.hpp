#pragma once
// `test::VirtualDisplay`: an X server (Xvfb) of the test process's own, for tests of windows.

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "executable_on_path.hpp"
#include "support/files.hpp"

namespace mjarm::test {

// An X server of the test's own (Debian's Xvfb), independent of anything else on the machine:
// - the server picks a free display number itself and reports it (-displayfd), atomically with
//   taking it, where `xvfb-run -a` guessed one from /tmp/.X*-lock files and raced every other
//   program starting an X server at the same time;
// - the test waits for that report (the server accepts connections from then on), bounded;
// - the server is killed and reaped when the display goes out of scope (at the test process's
//   exit, whatever the tests' outcome), and dies with the test process if that is killed or
//   crashes (PR_SET_PDEATHSIG).
class VirtualDisplay {
 public:
  VirtualDisplay() {
    const std::string xvfb = executable_on_path("Xvfb");
    if (xvfb.empty()) {
      error_ =
          "no Xvfb on PATH: the viewer test needs one; scripts/setup.sh installs Debian's xvfb";
      return;
    }
    int ready[2];
    if (::pipe2(ready, O_CLOEXEC) != 0) {
      error_ = std::string("pipe: ") + std::strerror(errno);
      return;
    }
    const std::filesystem::path log = std::filesystem::temp_directory_path() /
                                      ("mjarm_viewer_xvfb_" + std::to_string(::getpid()) + ".log");
    log_ = log;
    // everything the child needs, prepared before fork
    std::vector<std::string> args = {xvfb,        "-displayfd", std::to_string(ready[1]),
                                     "-screen",   "0",          "1280x1024x24",
                                     "-nolisten", "tcp"};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t parent = ::getpid();
    pid_ = ::fork();
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(127);
      ::setpgid(0, 0);                // the test's terminal signals are not the server's
      ::fcntl(ready[1], F_SETFD, 0);  // the report pipe stays open across exec
      const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (out >= 0) {
        ::dup2(out, STDOUT_FILENO);
        ::dup2(out, STDERR_FILENO);
      }
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(ready[1]);
    if (pid_ < 0) {
      error_ = std::string("fork: ") + std::strerror(errno);
      ::close(ready[0]);
      return;
    }
    // the display number, then a newline, once the server listens; bounded
    std::string number;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (number.find('\n') == std::string::npos) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) break;
      pollfd wait{ready[0], POLLIN, 0};
      if (::poll(&wait, 1, static_cast<int>(left.count())) <= 0) continue;
      char buffer[16];
      const ssize_t n = ::read(ready[0], buffer, sizeof buffer);
      if (n <= 0) break;  // the server exited before it was ready
      number.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(ready[0]);
    if (number.find('\n') == std::string::npos) {
      error_ = "Xvfb did not report a display within 60 s: " + slurp(log_);
      stop();
      return;
    }
    display_ = ":" + number.substr(0, number.find('\n'));
  }
  ~VirtualDisplay() { stop(); }
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;

  /// ":N", or empty when the server did not start (see `error`).
  const std::string& display() const { return display_; }
  const std::string& error() const { return error_; }

 private:
  // SIGTERM, then SIGKILL if the server has not ended within 10 s; reaped either way
  void stop() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int status = 0;
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (::waitpid(pid_, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
          ::kill(pid_, SIGKILL);
          while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
          }
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      pid_ = -1;
    }
    if (!log_.empty()) {
      std::error_code ec;
      std::filesystem::remove(log_, ec);
      log_.clear();
    }
  }

  pid_t pid_ = -1;
  std::string display_;
  std::string error_;
  std::filesystem::path log_;
};

}  // namespace mjarm::test
