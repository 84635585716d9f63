#pragma once
/// @file
/// A full disk for tests, without root or a mount: code runs in a forked child whose files may not
/// grow past a limit (RLIMIT_FSIZE, with SIGXFSZ ignored so that a write past the limit fails
/// with EFBIG, "File too large", as a write to a full disk fails with ENOSPC). Pipes are not
/// limited: what the child reports comes back through them.

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <exception>
#include <filesystem>
#include <string>
#include <vector>

namespace mjarm::test {

/// How a limited child ended.
struct LimitedRun {
  int exit_code = -1;  ///< -1 when it died of a signal
  std::string out;     ///< what the body returned, or the child's stdout
  std::string err;     ///< the message of the exception the body threw, or the child's stderr
};

namespace limit_detail {

// every byte of @p fds until each is closed (both drained together: no pipe fills up)
inline std::vector<std::string> drain(std::vector<int> fds) {
  std::vector<std::string> text(fds.size());
  std::vector<pollfd> polls;
  for (int fd : fds) polls.push_back({fd, POLLIN, 0});
  std::size_t open = fds.size();
  char buffer[4096];
  while (open > 0) {
    if (::poll(polls.data(), polls.size(), -1) < 0) continue;
    for (std::size_t i = 0; i < polls.size(); ++i) {
      if (polls[i].fd < 0 || polls[i].revents == 0) continue;
      const ssize_t n = ::read(polls[i].fd, buffer, sizeof(buffer));
      if (n > 0) {
        text[i].append(buffer, static_cast<std::size_t>(n));
      } else {
        ::close(polls[i].fd);
        polls[i].fd = -1;
        --open;
      }
    }
  }
  return text;
}

inline void limit_file_size(std::size_t bytes) {
  const rlimit limit{static_cast<rlim_t>(bytes), static_cast<rlim_t>(bytes)};
  ::setrlimit(RLIMIT_FSIZE, &limit);
  ::signal(SIGXFSZ, SIG_IGN);  // kept across exec: a write past the limit fails with EFBIG
}

inline void write_all(int fd, const std::string& text) {
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

inline int wait_for(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace limit_detail

/// Runs @p body (returning a std::string) in a forked child whose files may grow to @p bytes at
/// most. Exit code 0 and `out` = what it returned, or exit code 1 and `err` = the message of what
/// it threw.
template <class Body>
LimitedRun with_file_size_limit(std::size_t bytes, Body&& body) {
  int out[2], err[2];
  if (::pipe(out) != 0 || ::pipe(err) != 0) return {};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(out[0]);
    ::close(err[0]);
    limit_detail::limit_file_size(bytes);
    int code = 0;
    try {
      limit_detail::write_all(out[1], body());
    } catch (const std::exception& e) {
      limit_detail::write_all(err[1], e.what());
      code = 1;
    }
    ::_exit(code);  // no atexit handlers, no test framework teardown in the child
  }
  ::close(out[1]);
  ::close(err[1]);
  LimitedRun run;
  if (pid < 0) {
    ::close(out[0]);
    ::close(err[0]);
    return run;
  }
  const std::vector<std::string> text = limit_detail::drain({out[0], err[0]});
  run.out = text[0];
  run.err = text[1];
  run.exit_code = limit_detail::wait_for(pid);
  return run;
}

/// Runs @p program with @p args in @p cwd, its files limited to @p bytes; stdout and stderr come
/// back through pipes (not limited).
inline LimitedRun run_with_file_size_limit(std::size_t bytes, const std::string& program,
                                           const std::vector<std::string>& args,
                                           const std::filesystem::path& cwd) {
  int out[2], err[2];
  if (::pipe(out) != 0 || ::pipe(err) != 0) return {};
  std::vector<std::string> all{program};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    ::dup2(err[1], STDERR_FILENO);
    for (int fd : {out[0], out[1], err[0], err[1]}) ::close(fd);
    if (::chdir(cwd.c_str()) != 0) ::_exit(127);
    limit_detail::limit_file_size(bytes);
    ::execv(program.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(out[1]);
  ::close(err[1]);
  LimitedRun run;
  if (pid < 0) {
    ::close(out[0]);
    ::close(err[0]);
    return run;
  }
  const std::vector<std::string> text = limit_detail::drain({out[0], err[0]});
  run.out = text[0];
  run.err = text[1];
  run.exit_code = limit_detail::wait_for(pid);
  return run;
}

}  // namespace mjarm::test
