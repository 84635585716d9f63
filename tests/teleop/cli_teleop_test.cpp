// `mjarm bimanual` and `mjarm replay` as a person runs them: the scripted lift recorded to a
// session file, replayed headless to the same state; a truncated file and a file replayed on
// another model are clear errors (exit 1), usage mistakes exit 2.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "support/files.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;

struct CliOutcome {
  int status = -1;
  std::string out;
  std::string err;
};

CliOutcome run_cli(const std::string& args) {
  const fs::path err = test::scratch() / "cli_stderr.txt";
  CliOutcome r;
  FILE* pipe = popen(("'" MJARM_CLI "' " + args + " 2>'" + err.string() + "'").c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buffer{};
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
    r.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = test::slurp(err);
  return r;
}

TEST(CliTeleop, BimanualRecordsASessionThatReplaysExactly) {
  const fs::path session = test::scratch() / "lift.session";
  const CliOutcome lift = run_cli("bimanual --json --record-session '" + session.string() + "'");
  ASSERT_EQ(lift.status, 0) << lift.err;
  const auto doc = nlohmann::json::parse(lift.out);
  EXPECT_TRUE(doc["success"].get<bool>());
  EXPECT_NEAR(doc["lifted"].get<double>(), 0.2, 0.01);
  const CliOutcome replay = run_cli("replay --json '" + session.string() + "'");
  ASSERT_EQ(replay.status, 0) << replay.err;
  const auto r = nlohmann::json::parse(replay.out);
  EXPECT_TRUE(r["deterministic"].get<bool>());
  EXPECT_EQ(r["ticks"], doc["ticks"]);
  EXPECT_EQ(r["digest"], r["recorded_digest"]);

  // another model: refused, naming both
  const CliOutcome other = run_cli("replay '" + session.string() + "' --model dual_arm");
  EXPECT_EQ(other.status, 1);
  EXPECT_NE(other.err.find("recorded on model 'dual_arm_box'"), std::string::npos) << other.err;
  // truncated: the last 30 bytes gone
  const std::string text = test::slurp(session);
  const fs::path cut = test::scratch() / "cut.session";
  std::ofstream(cut, std::ios::binary) << text.substr(0, text.size() - 30);
  const CliOutcome truncated = run_cli("replay '" + cut.string() + "'");
  EXPECT_EQ(truncated.status, 1);
  EXPECT_NE(truncated.err.find("cut.session"), std::string::npos) << truncated.err;
  EXPECT_NE(truncated.err.find("truncated"), std::string::npos) << truncated.err;
}

TEST(CliTeleop, UsageErrorsExitTwo) {
  EXPECT_EQ(run_cli("replay").status, 2);
  EXPECT_EQ(run_cli("bimanual --mode fast").status, 2);
  EXPECT_EQ(run_cli("bimanual --lift 2").status, 2);
  // the video's sizes and rates, on the commands themselves (the shared checker's bounds)
  const std::pair<const char*, const char*> refused[] = {
      {"bimanual --video v.mp4 --size 20000x20000", "--size: size '20000x20000' must be between"},
      {"bimanual --video v.mp4 --fps 1e6", "--fps: '1e6' is not a number from 1 to 240"},
      {"replay s --video v.mp4 --size 20000x20000",
       "--size: size '20000x20000' must be between"}};
  for (const auto& [args, message] : refused) {
    const CliOutcome run = run_cli(args);
    EXPECT_EQ(run.status, 2) << args;
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
  }
  const CliOutcome missing = run_cli("replay '" + (test::scratch() / "absent").string() + "'");
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.err.find("absent"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace mjarm
