#include "mjarm/plot/gnuplot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "plot/plot_test_support.hpp"

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

}  // namespace
}  // namespace mjarm::plot
