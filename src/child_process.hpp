#pragma once
/// @file
/// Starting and stopping a helper program (ffmpeg, gnuplot) so that it never outlives mjarm:
/// fork + execv with an argv array (never a shell), PR_SET_PDEATHSIG in the child, and kill +
/// reap on every error path.

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace mjarm {

/// Where a child's standard streams go: a file descriptor of the parent, or -1 for /dev/null.
struct ChildStreams {
  int in = -1;
  int out = -1;
  int err = -1;
};

/// Starts @p args[0] (a path) with arguments @p args and the parent's environment.
///
/// The child gets SIGKILL when the thread that started it ends (PR_SET_PDEATHSIG, set before
/// exec, and the child ends itself when the parent is already gone by then), so it never
/// outlives mjarm, even after a SIGKILL. With @p own_process_group it leads a process group of
/// its own: a terminal's Ctrl-C then reaches mjarm only, which ends the child's input itself.
/// SIGINT, SIGTERM and SIGPIPE have their default action in the child and no signal is blocked.
/// @return the child's pid, or -1 with @p error set to the errno of the failed fork or exec.
inline pid_t start_child(const std::vector<std::string>& args, ChildStreams streams,
                         bool own_process_group, int& error) {
  error = 0;
  // everything the child needs is prepared before fork: after it, only system calls
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  int report[2];  // the child writes exec's errno here; end of file means exec succeeded
  if (::pipe2(report, O_CLOEXEC) != 0) {
    error = errno;
    return -1;
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    error = errno;
    ::close(report[0]);
    ::close(report[1]);
    return -1;
  }
  if (pid == 0) {
    int failure = 0;
    if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0) failure = errno;
    if (::getppid() != parent) ::_exit(127);  // the parent died before prctl took effect
    if (own_process_group && failure == 0 && ::setpgid(0, 0) != 0) failure = errno;
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    for (const int signal : {SIGINT, SIGTERM, SIGPIPE, SIGQUIT, SIGHUP})
      ::sigaction(signal, &default_action, nullptr);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    const int targets[3] = {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO};
    const int sources[3] = {streams.in, streams.out, streams.err};
    for (int k = 0; k < 3 && failure == 0; ++k) {
      int fd = sources[k];
      if (fd < 0) fd = ::open("/dev/null", k == 0 ? O_RDONLY : O_WRONLY);
      if (fd < 0) {
        failure = errno;
      } else if (fd == targets[k]) {
        ::fcntl(fd, F_SETFD, 0);  // dup2 onto itself would keep close-on-exec
      } else if (::dup2(fd, targets[k]) < 0) {
        failure = errno;
      }
    }
    if (failure == 0) {
      ::execv(argv[0], argv.data());
      failure = errno;
    }
    while (::write(report[1], &failure, sizeof failure) < 0 && errno == EINTR) {
    }
    ::_exit(127);
  }
  ::close(report[1]);
  int child_error = 0;
  ssize_t n = 0;
  while ((n = ::read(report[0], &child_error, sizeof child_error)) < 0 && errno == EINTR) {
  }
  ::close(report[0]);
  if (n > 0) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    error = child_error != 0 ? child_error : ECHILD;
    return -1;
  }
  return pid;
}

/// Waits for child @p pid until @p deadline; true (and its wait @p status) when it ended.
inline bool wait_child_until(pid_t pid, std::chrono::steady_clock::time_point deadline,
                             int& status) {
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) return true;
    if (done < 0 && errno != EINTR) {
      status = 0;
      return true;  // not our child any more: nothing left to wait for
    }
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

/// Kills child @p pid (its whole process group when @p group) with SIGKILL and reaps it.
inline int kill_child(pid_t pid, bool group) noexcept {
  ::kill(group ? -pid : pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

}  // namespace mjarm
