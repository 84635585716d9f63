#include "mjarm/plot/gnuplot.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>
#include <vector>

#include "executable_on_path.hpp"
#include "mjarm/error.hpp"

extern char** environ;

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

std::string read_log(int fd) {
  std::string text;
  ::lseek(fd, 0, SEEK_SET);
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof(buffer))) > 0;)
    text.append(buffer, static_cast<std::size_t>(n));
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  if (text.size() > 2000) text = text.substr(0, 2000) + " …";
  return text;
}

}  // namespace

std::string gnuplot_string(std::string_view text) {
  std::string out;
  bool in_quotes = false;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte == 0) continue;
    if (byte < 0x20 || byte == 0x7f || c == '\'') {
      // a control character or a quote: "\ooo" on its own, between single-quoted runs
      if (in_quotes) out += '\'';
      if (!out.empty()) out += '.';
      const char octal[] = {'"',
                            '\\',
                            static_cast<char>('0' + (byte >> 6)),
                            static_cast<char>('0' + ((byte >> 3) & 7)),
                            static_cast<char>('0' + (byte & 7)),
                            '"'};
      out.append(octal, sizeof octal);
      in_quotes = false;
      continue;
    }
    if (!in_quotes) {
      if (!out.empty()) out += '.';
      out += '\'';
      in_quotes = true;
    }
    out += c;
  }
  if (in_quotes) out += '\'';
  return out.empty() ? "''" : out;
}

fs::path find_gnuplot() {
  const std::string gnuplot = executable_on_path("gnuplot");
  if (gnuplot.empty()) {
    throw Error(
        "gnuplot was not found on PATH; install the Debian package gnuplot-nox "
        "(apt-get install gnuplot-nox) to draw plots");
  }
  return gnuplot;
}

void run_gnuplot(const fs::path& script, double timeout_s) {
  const fs::path gnuplot = find_gnuplot();
  // gnuplot's messages go to an unlinked temporary file: no pipe to drain while we wait
  char log_name[] = "/tmp/mjarm-gnuplot-XXXXXX";
  const int log = ::mkstemp(log_name);
  if (log < 0)
    throw Error(std::string("cannot create a log file for gnuplot: ") + std::strerror(errno));
  ::unlink(log_name);

  std::string program = gnuplot.string(), name = script.string();
  std::vector<char*> argv{program.data(), name.data(), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, log, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log, STDERR_FILENO);
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    ::close(log);
    throw Error("cannot start gnuplot ('" + program + "') on '" + script.string() +
                "': " + std::strerror(spawned));
  }

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid || (done < 0 && errno != EINTR)) break;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      ::close(log);
      throw Error("gnuplot did not finish '" + script.string() + "' within " +
                  std::to_string(timeout_s) + " s and was stopped");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const std::string messages = read_log(log);
  ::close(log);
  if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    const std::string how = WIFEXITED(status)
                                ? "exited with status " + std::to_string(WEXITSTATUS(status))
                                : "was killed by signal " + std::to_string(WTERMSIG(status));
    throw Error("gnuplot " + how + " on '" + script.string() +
                "': " + (messages.empty() ? "no message" : messages));
  }
}

}  // namespace mjarm::plot
