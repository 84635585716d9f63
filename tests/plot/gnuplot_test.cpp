#include "mjarm/plot/gnuplot.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "plot/plot_test_support.hpp"
#include "support/error_message.hpp"

namespace mjarm::plot {
namespace {

namespace fs = std::filesystem;

// Texts that would run `touch NAME` in gnuplot's working folder if they were written into a
// script raw (or quoted naively): newline, quotes, backquote, $(), a continued line, `system`.
std::vector<std::string> hostile_texts() {
  return {"a\nsystem \"touch PWNED1\"\n",
          "b'\nsystem 'touch PWNED2'\nprint '",
          "c`touch PWNED3`",
          "d$(touch PWNED4)",
          "e\"; system \"touch PWNED5\"; \"",
          "f\\\nsystem \"touch PWNED6\"",
          "g\r\nsystem \"touch PWNED7\" # \\",
          "h'' @PWNED8 \t \x7f \\ ' \"",
          "\xc2\xb5m \xe2\x80\x94 plain UTF-8"};
}

TEST(GnuplotString, PlainTextIsOneSingleQuotedLiteral) {
  EXPECT_EQ(gnuplot_string("joint torques [N m]"), "'joint torques [N m]'");
  EXPECT_EQ(gnuplot_string(""), "''");
  EXPECT_EQ(gnuplot_string("it's"), "'it'.\"\\047\".'s'");
  EXPECT_EQ(gnuplot_string("a\nb"), "'a'.\"\\012\".'b'");
  EXPECT_EQ(gnuplot_string("\n"), "\"\\012\"");
  EXPECT_EQ(gnuplot_string(std::string("x\0y", 3)), "'xy'");  // NUL dropped
}

TEST(GnuplotString, NeverBreaksALineNorEndsWithABackslash) {
  for (const std::string& text : hostile_texts()) {
    const std::string quoted = gnuplot_string(text);
    EXPECT_EQ(quoted.find('\n'), std::string::npos) << quoted;
    EXPECT_EQ(quoted.find('\r'), std::string::npos) << quoted;
    EXPECT_NE(quoted.back(), '\\') << quoted;
  }
}

// gnuplot itself reads every quoted text back exactly, and runs none of the commands in them
TEST(GnuplotString, GnuplotReadsTheTextBackExactlyAndRunsNothing) {
  test::TempDir dir("plot-quote");
  const fs::path printed = dir.path() / "printed.txt";
  std::string script = "set print " + gnuplot_string(printed.string()) + "\n";
  std::string expected;
  for (const std::string& text : hostile_texts()) {
    script += "# " + gnuplot_string(text) + " (a comment holding the text)\n";
    script += "print " + gnuplot_string(text) + "\n";
    expected += text + "\n";
  }
  script += "unset print\n";
  test::write_file(dir.path() / "quote.gp", script);
  // gnuplot runs in this process's working folder: make it the scratch folder
  const fs::path saved = fs::current_path();
  fs::current_path(dir.path());
  try {
    run_gnuplot(dir.path() / "quote.gp", 30.0);
  } catch (...) {
    fs::current_path(saved);
    throw;
  }
  fs::current_path(saved);
  EXPECT_EQ(test::read_text(printed), expected);
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_NE(entry.path().filename().string().rfind("PWNED", 0), 0u) << entry.path();
}

TEST(Gnuplot, AFailingScriptReportsGnuplotsMessage) {
  test::TempDir dir("plot-gnuplot");
  test::write_file(dir.path() / "bad.gp", "set terminal pngcairo\nthis is not gnuplot\n");
  try {
    run_gnuplot(dir.path() / "bad.gp", 30.0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gnuplot exited with status"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
  }
}

TEST(Gnuplot, TheTimeoutMustBeAPositiveFiniteNumber) {
  test::TempDir dir("plot-bad-timeout");
  test::write_file(dir.path() / "empty.gp", "\n");
  for (const double timeout : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    try {
      run_gnuplot(dir.path() / "empty.gp", timeout);
      ADD_FAILURE() << "no error for " << timeout;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("gnuplot timeout must be a finite number"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(Gnuplot, ARunawayScriptIsStoppedAtTheTimeout) {
  test::TempDir dir("plot-timeout");
  test::write_file(dir.path() / "slow.gp", "pause 30\n");
  try {
    run_gnuplot(dir.path() / "slow.gp", 0.3);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("did not finish"), std::string::npos) << e.what();
  }
}

// issue 29: Ctrl-C (or SIGTERM) while gnuplot draws stops it at once, so the caller can remove
// what it drew. The signal is sent once gnuplot has started the script: its first command
// opens a FIFO this test reads, and says so through it (an event, not a delay).
TEST(Gnuplot, AnInterruptStopsItWhileItDraws) {
  test::TempDir dir("plot-interrupt");
  const fs::path fifo = dir.path() / "started";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  test::write_file(dir.path() / "long.gp", "set print " + gnuplot_string(fifo.string()) +
                                               "\nprint 'drawing'\nunset print\npause 60\n");
  const InterruptGuard interrupts;
  std::thread signaller([&] {
    std::ifstream started(fifo);  // opens once gnuplot opened the FIFO to write
    std::string line;
    if (std::getline(started, line) && line == "drawing") ::kill(::getpid(), SIGINT);
  });
  const std::string message = test::error_of([&] { run_gnuplot(dir.path() / "long.gp", 120.0); });
  // gnuplot never reached the FIFO (it failed first): the reader is let go all the same
  const int unblock = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  if (unblock >= 0) ::close(unblock);
  signaller.join();
  EXPECT_NE(message.find("gnuplot was stopped on '"), std::string::npos) << message;
  EXPECT_NE(message.find("': interrupted"), std::string::npos) << message;
  // still pending: a later drawing does not start
  const std::string again = test::error_of([&] { run_gnuplot(dir.path() / "long.gp", 120.0); });
  EXPECT_NE(again.find("gnuplot was not started on '"), std::string::npos) << again;
}

}  // namespace
}  // namespace mjarm::plot
