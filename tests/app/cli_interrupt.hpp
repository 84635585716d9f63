#pragma once
/// @file
/// Starts the built `mjarm` in the background for the Ctrl-C tests. SIGINT is sent on an event
/// the program emits — its progress line (drawn when standard error is a terminal: here a
/// pseudo-terminal) showing work done — never after a delay or an amount of CPU time, so a slow
/// or busy machine cannot make the verdict differ.

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/types.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"

namespace mjarm::test {

/// A CLI process started by `start_cli_on_terminal`.
struct StartedCli {
  pid_t pid = -1;
  std::filesystem::path out;
  int terminal = -1;                  ///< pseudo-terminal master of stderr
  std::shared_ptr<std::string> seen;  ///< what stderr showed on the terminal so far
};

/// Starts the CLI with @p args, stdout into a file named after @p tag and stderr on a
/// pseudo-terminal, as for a user at a terminal: long work draws its progress line there.
inline StartedCli start_cli_on_terminal(const std::vector<std::string>& args,
                                        const std::string& tag,
                                        const std::filesystem::path& cwd = scratch()) {
  StartedCli started;
  started.out = scratch() / (tag + ".out");
  started.seen = std::make_shared<std::string>();
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0) {
    ADD_FAILURE() << "no pseudo-terminal: " << std::strerror(errno);
    return started;
  }
  const int slave = open(ptsname(master), O_RDWR | O_NOCTTY);
  termios mode{};
  tcgetattr(slave, &mode);
  mode.c_oflag &= ~static_cast<tcflag_t>(OPOST);  // the program's bytes as written (no \r\n)
  tcsetattr(slave, TCSANOW, &mode);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, started.out.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, slave, STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, master);
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
  close(slave);  // the child holds it: reading the master ends (EIO) when the child is gone
  started.terminal = master;
  return started;
}

/// Reads what the terminal shows, for up to @p wait_ms; false once the child side is closed.
inline bool read_terminal(const StartedCli& cli, int wait_ms) {
  pollfd fd{cli.terminal, POLLIN, 0};
  if (poll(&fd, 1, wait_ms) <= 0) return true;
  char buffer[4096];
  const ssize_t n = read(cli.terminal, buffer, sizeof(buffer));
  if (n > 0) cli.seen->append(buffer, static_cast<std::size_t>(n));
  return n > 0 || (n < 0 && errno == EINTR);
}

/// The count of the last progress line drawn so far ("label ███░░ 12.5% (DONE/TOTAL)"), or -1.
inline long long progress_done(const std::string& seen) {
  static const std::regex line(R"(\((\d+)/\d+\))");
  long long done = -1;
  for (auto it = std::sregex_iterator(seen.begin(), seen.end(), line); it != std::sregex_iterator();
       ++it)
    done = std::stoll((*it)[1]);
  return done;
}

/// Sends @p signal (SIGINT: Ctrl-C) once the progress line on the terminal shows at least
/// @p done units of work finished (so the work has started, and got that far). Nothing is sent
/// if the process ends first.
inline void interrupt_after_progress(const StartedCli& cli, long long done = 1,
                                     int signal = SIGINT) {
  if (cli.pid < 0 || cli.terminal < 0) return;
  while (read_terminal(cli, 100)) {
    if (progress_done(*cli.seen) >= done) {
      kill(cli.pid, signal);
      return;
    }
  }
}

/// Waits for the process to end and collects what it did (stderr: what the terminal showed).
inline CliRun finish_cli(const StartedCli& cli) {
  CliRun run;
  if (cli.pid < 0) return run;
  // drained to the end, or a full terminal would block the program
  while (read_terminal(cli, 100)) {
  }
  close(cli.terminal);
  int status = 0;
  while (waitpid(cli.pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.signaled = WIFSIGNALED(status);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = slurp(cli.out);
  run.err = *cli.seen;
  return run;
}

}  // namespace mjarm::test
