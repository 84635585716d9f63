#include "mjarm/plot/gnuplot.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>

#include "child_process.hpp"
#include "executable_on_path.hpp"
#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/number_text.hpp"

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
  if (!(timeout_s > 0.0) || !std::isfinite(timeout_s))
    throw Error("gnuplot timeout must be a finite number of seconds > 0, got " +
                number_text(timeout_s));
  const fs::path gnuplot = find_gnuplot();
  if (interrupt_requested())
    throw Error("gnuplot was not started on '" + script.string() + "': interrupted");
  // gnuplot's messages go to an unlinked temporary file: no pipe to drain while we wait
  char log_name[] = "/tmp/mjarm-gnuplot-XXXXXX";
  const int log = ::mkostemp(log_name, O_CLOEXEC);
  if (log < 0)
    throw Error(std::string("cannot create a log file for gnuplot: ") + std::strerror(errno));
  ::unlink(log_name);

  // an argv array, no shell; the child dies with mjarm (child_process.hpp)
  const std::string program = gnuplot.string();
  int error = 0;
  const pid_t pid = start_child({program, script.string()}, {-1, log, log}, false, error);
  if (pid < 0) {
    ::close(log);
    throw Error("cannot start gnuplot ('" + program + "') on '" + script.string() +
                "': " + std::strerror(error));
  }

  const auto deadline =
      std::chrono::steady_clock::now() +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(std::min(timeout_s, 1e7)));  // no overflow
  // waited for in slices: Ctrl-C or SIGTERM (under an InterruptGuard) stops it at once, and the
  // caller removes what it drew (plot_files.hpp)
  int status = 0;
  for (;;) {
    const auto slice =
        std::min(deadline, std::chrono::steady_clock::now() + std::chrono::milliseconds(100));
    if (wait_child_until(pid, slice, status)) break;
    if (interrupt_requested()) {
      kill_child(pid, false);
      ::close(log);
      throw Error("gnuplot was stopped on '" + script.string() + "': interrupted");
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      kill_child(pid, false);
      ::close(log);
      throw Error("gnuplot did not finish '" + script.string() + "' within " +
                  number_text(timeout_s) + " s and was stopped");
    }
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
