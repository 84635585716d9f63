// Two writers of one output file (issue 29's bad-input matrix, "concurrent writers"): a single
// file takes no lock by design (output folders do: output_folder_test.cpp). Each writer writes
// its own hidden temporary file and renames it over the target once complete
// (include/mjarm/file_writer.hpp), so the last complete file stays: never a mix of the two, never
// a cut file, never a temporary file left. Checked on FileWriter itself and on one command of
// each writer class: `--out` (CSV, PNG), `--video` (ffmpeg's file), `--record-session`.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "mjarm/file_writer.hpp"
#include "support/files.hpp"
#include "support/running_process.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::RunningProcess;
using mjarm::test::scratch;
using mjarm::test::slurp;

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(ConcurrentWriters, TwoFileWritersOfOnePathLeaveTheLastWholeFile) {
  const fs::path dir = scratch() / "two_file_writers";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path path = dir / "same.csv";
  std::ofstream(path) << "old\n";
  // small buffers: the bytes of both reach their temporary files interleaved
  mjarm::FileWriter first(path, mjarm::FileWriter::Mode::replace, "CSV", 16);
  mjarm::FileWriter second(path, mjarm::FileWriter::Mode::replace, "CSV", 16);
  std::string first_text, second_text;
  for (int k = 0; k < 200; ++k) {
    const std::string a = "first," + std::to_string(k) + "\n";
    const std::string b = "second," + std::to_string(k) + "\n";
    ASSERT_TRUE(first.write(a));
    ASSERT_TRUE(second.write(b));
    first_text += a;
    second_text += b;
  }
  // until a writer commits, the old file is what readers see
  EXPECT_EQ(slurp(path), "old\n");
  EXPECT_EQ(names_in(dir).size(), 3u);  // the file and two temporary files
  ASSERT_TRUE(first.close()) << first.failure();
  EXPECT_EQ(slurp(path), first_text);
  ASSERT_TRUE(second.close()) << second.failure();
  EXPECT_EQ(slurp(path), second_text);  // the last complete file stays, whole
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"same.csv"});

  // a writer abandoned beside a committed one leaves the committed file and nothing else
  {
    mjarm::FileWriter kept(path, mjarm::FileWriter::Mode::replace, "CSV", 16);
    mjarm::FileWriter dropped(path, mjarm::FileWriter::Mode::replace, "CSV", 16);
    ASSERT_TRUE(kept.write(first_text));
    ASSERT_TRUE(dropped.write(second_text));
    ASSERT_TRUE(kept.close());
  }
  EXPECT_EQ(slurp(path), first_text);
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"same.csv"});
}

/// @p args with every "@" replaced by @p path, after the CLI's path.
std::vector<std::string> writing_to(const std::vector<std::string>& args, const fs::path& path) {
  std::vector<std::string> argv{MJARM_CLI};
  for (const std::string& a : args) argv.push_back(a == "@" ? path.string() : a);
  return argv;
}

/// Runs @p a and @p b alone, each to its own file (what each writes whole), then both at once to
/// one file of an empty folder: both succeed, the file is one of the two whole outputs, and
/// nothing is left beside it. "@" in the arguments stands for the output file.
void expect_the_last_whole_file_stays(const std::string& name, const std::vector<std::string>& a,
                                      const std::vector<std::string>& b,
                                      const std::string& extension,
                                      const std::vector<std::string>& env = {}) {
  const fs::path dir = scratch() / ("concurrent_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "both");
  std::string alone[2];
  for (int i = 0; i < 2; ++i) {
    const fs::path file = dir / ((i == 0 ? "a" : "b") + extension);
    RunningProcess run(writing_to(i == 0 ? a : b, file), dir, env);
    ASSERT_TRUE(run.wait(900)) << name << " did not end";
    ASSERT_EQ(run.exit_code(), 0) << name << ": " << run.err();
    alone[i] = slurp(file);
  }
  ASSERT_NE(alone[0], alone[1]) << name << ": the two runs must write different files";
  const fs::path same = dir / "both" / ("same" + extension);
  // started together; neither waits for the other
  RunningProcess first(writing_to(a, same), dir, env);
  RunningProcess second(writing_to(b, same), dir, env);
  ASSERT_TRUE(first.wait(900)) << name << " did not end";
  ASSERT_TRUE(second.wait(900)) << name << " did not end";
  EXPECT_EQ(first.exit_code(), 0) << name << ": " << first.err();
  EXPECT_EQ(second.exit_code(), 0) << name << ": " << second.err();
  const std::string kept = slurp(same);
  EXPECT_TRUE(kept == alone[0] || kept == alone[1])
      << name << ": " << kept.size() << " bytes, neither run's whole file (" << alone[0].size()
      << " or " << alone[1].size() << " bytes)";
  EXPECT_EQ(names_in(dir / "both"), std::vector<std::string>{"same" + extension}) << name;
}

TEST(ConcurrentWriters, TwoRunsWritingOneOutFileLeaveOneWholeFile) {
  const fs::path waypoints = scratch() / "concurrent_five.json";
  std::ofstream(waypoints)
      << R"({"waypoints": [{"position": [0.45, 0.0, 0.50]}, {"position": [0.45, 0.20, 0.40]},
  {"position": [0.35, 0.25, 0.35]}, {"position": [0.30, 0.10, 0.45]},
  {"position": [0.40, -0.15, 0.50]}]})";
  expect_the_last_whole_file_stays(
      "workspace", {"workspace", "planar2", "--samples", "20000", "--seed", "1", "--out", "@"},
      {"workspace", "planar2", "--samples", "20000", "--seed", "2", "--out", "@"}, ".csv");
  expect_the_last_whole_file_stays(
      "traj", {"traj", "quintic", "--start", "0", "0", "--target", "1", "1", "--out", "@"},
      {"traj", "quintic", "--start", "0", "0", "--target", "1", "-1", "--out", "@"}, ".csv");
  expect_the_last_whole_file_stays(
      "plan",
      {"plan", "panda_torque", "--waypoints", waypoints.string(), "--rate", "100", "--out", "@"},
      {"plan", "panda_torque", "--waypoints", waypoints.string(), "--rate", "200", "--out", "@"},
      ".csv");
  // Mesa's JIT allocations are no leak of mjarm's (tests/CMakeLists.txt)
  expect_the_last_whole_file_stays(
      "render", {"render", "planar2", "--size", "160x120", "--azimuth", "0", "--out", "@"},
      {"render", "planar2", "--size", "160x120", "--azimuth", "90", "--out", "@"}, ".png",
      {"ASAN_OPTIONS=detect_leaks=0"});
}

// the test's name holds "Video": in the sanitized build it runs without leak checking, as every
// test that renders (tests/CMakeLists.txt); the shelf pick (0.4 s simulated) at 10 frames per
// second, 5 small frames, keeps the runs short; two seeds, two pick points, two videos
TEST(ConcurrentWriters, TwoRunsWritingOneVideoLeaveOneWholeVideo) {
  expect_the_last_whole_file_stays(
      "shelf_pick_video",
      {"run", "shelf-pick", "--seed", "1", "--size", "64x48", "--fps", "10", "--video", "@"},
      {"run", "shelf-pick", "--seed", "2", "--size", "64x48", "--fps", "10", "--video", "@"},
      ".mp4");
}

TEST(ConcurrentWriters, TwoRunsRecordingOneSessionLeaveOneWholeSession) {
  expect_the_last_whole_file_stays(
      "session", {"bimanual", "--lift", "0.1", "--record-session", "@"},
      {"bimanual", "--lift", "0.2", "--record-session", "@"}, ".session");
}

}  // namespace
