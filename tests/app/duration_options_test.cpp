// The rule for every duration or timeout option of the CLI (options.hpp, duration_at_most): a
// value out of the documented range is a usage error (exit 2) naming the range, before any
// work. `ik --timeout-ms 1e13` used to overflow the solver's deadline, `bench ik --timeout-ms
// 1e308` reported 0 % success with exit 0, and `run --control-period 1e300` ran for ever.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/cli_runner.hpp"

namespace {

using mjarm::test::CliRun;
using mjarm::test::run_cli;

/// One duration option: the command line before it, its name, the range its message names.
struct DurationOption {
  std::vector<std::string> command;
  std::string option;
  std::string range;
  std::vector<std::string> rejected;
};

TEST(DurationOptions, EveryOneIsBoundedWithAClearError) {
  const std::vector<std::string> common{"1e13", "1e308", "1e999", "nan", "inf", "-1", "abc", ""};
  const std::vector<DurationOption> options{
      {{"ik", "panda", "--pos", "0.4", "0", "0.5"},
       "--timeout-ms",
       "more than 0 and at most 60000",
       {"0", "60000.5"}},
      {{"bench", "ik", "panda", "--samples", "1"},
       "--timeout-ms",
       "more than 0 and at most 60000",
       {"0", "60001"}},
      {{"run", "shelf-pick"}, "--control-period", "from 0 and at most 1", {"1.002"}},
      {{"run", "shelf-pick"}, "--settle-time", "more than 0 and at most 60", {"0", "61"}},
  };
  for (const DurationOption& o : options) {
    std::vector<std::string> values = common;
    values.insert(values.end(), o.rejected.begin(), o.rejected.end());
    for (const std::string& value : values) {
      std::vector<std::string> args = o.command;
      args.insert(args.end(), {o.option, value});
      SCOPED_TRACE(o.option + " " + value);
      const CliRun run = run_cli(args);
      EXPECT_FALSE(run.signaled);
      EXPECT_EQ(run.exit_code, 2) << run.err;
      EXPECT_EQ(run.err.rfind("mjarm: error: " + o.option, 0), 0u) << run.err;
      EXPECT_TRUE(run.out.empty()) << run.out;
      // CLI11 reports a missing value in its own words; every other value names the range
      if (!value.empty()) {
        EXPECT_NE(run.err.find(o.range), std::string::npos) << run.err;
      }
    }
  }
}

}  // namespace
