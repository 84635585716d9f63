// The rule for every file mjarm writes (docs/cli.md, "Files written"): one checked writer
// (include/mjarm/file_writer.hpp), so a full disk is an error naming the file and the reason and never
// leaves a truncated file. Checked on the sources (no other way to open a file for writing) and
// on the commands that write a single file, with a full disk made by RLIMIT_FSIZE.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "app/cli_runner.hpp"
#include "support/file_size_limit.hpp"

namespace {

namespace fs = std::filesystem;
using mjarm::test::run_cli;
using mjarm::test::scratch;
using mjarm::test::slurp;

// A word that every match of the writer pattern below holds.
constexpr const char* kWriterWords[] = {"fstream", "fopen(", "fwrite(", "O_WRONLY", "O_RDWR"};

// Lines of the library and the CLI that open or write a file some other way than FileWriter.
std::vector<std::string> unchecked_writers() {
  const fs::path root = fs::path(MJARM_MODELS_DIR).parent_path();
  // std::ofstream/fstream, fopen for writing or appending, fwrite, open(2) for writing
  const std::regex writer(
      R"(std::(o|)fstream\b|fopen\([^;]*"[wa]|\bfwrite\(|\bO_WRONLY\b|\bO_RDWR\b)");
  std::vector<std::string> found;
  for (const char* folder : {"src", "app"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
      const fs::path& path = entry.path();
      if (path.extension() != ".cpp" && path.extension() != ".hpp") continue;
      const std::string relative = fs::relative(path, root).string();
      if (relative == "src/file_writer.cpp") continue;  // the one checked writer
      std::ifstream in(path);
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        // the regular expression (slow: about 6 CPU-s over every line of the sanitized build)
        // only on the lines holding one of the words it needs
        const bool candidate =
            std::any_of(std::begin(kWriterWords), std::end(kWriterWords),
                        [&](const char* word) { return line.find(word) != std::string::npos; });
        if (!candidate || !std::regex_search(line, writer)) continue;
        // the CLI's output checks only prove, before the work, that a file can be created: they
        // create it empty (or open it) and remove it again, writing no data
        if (relative == "app/options.cpp") continue;
        // an output folder's lock file holds no data, only its holder's PID for messages
        if (relative == "src/folder_lock.cpp") continue;
        // a child's standard streams on /dev/null hold no data to lose
        if (line.find("\"/dev/null\"") != std::string::npos) continue;
        found.push_back(relative + ":" + std::to_string(number) + ": " + line);
      }
    }
  }
  return found;
}

TEST(FilesWritten, OnlyTheCheckedWriterOpensFilesForWriting) {
  const std::vector<std::string> found = unchecked_writers();
  std::string listing;
  for (const std::string& f : found) listing += f + "\n";
  EXPECT_TRUE(found.empty()) << "write files through FileWriter (include/mjarm/file_writer.hpp):\n"
                             << listing;
}

// Runs @p args (its last argument the file written, in @p cwd) with files limited to @p limit
// bytes over an old file: exit 1 naming the file and the reason, the old file as it was and
// nothing else beside it; then with the file on /dev/full (a device that refuses every byte).
void expect_full_disk_keeps_the_old_file(const fs::path& cwd, const std::vector<std::string>& args,
                                         std::size_t limit = 4096) {
  const std::string file = args.back();
  const std::size_t before = static_cast<std::size_t>(
      std::distance(fs::directory_iterator(cwd), fs::directory_iterator()));
  std::ofstream(cwd / file) << "old content\n";
  const mjarm::test::LimitedRun run =
      mjarm::test::run_with_file_size_limit(limit, MJARM_CLI, args, cwd);
  EXPECT_EQ(run.exit_code, 1) << file << "\n" << run.out << run.err;
  EXPECT_NE(run.err.find("'" + file + "': File too large"), std::string::npos) << run.err;
  EXPECT_EQ(slurp(cwd / file), "old content\n") << file;
  EXPECT_EQ(static_cast<std::size_t>(
                std::distance(fs::directory_iterator(cwd), fs::directory_iterator())),
            before + 1)
      << file;
  fs::remove(cwd / file);

  std::vector<std::string> full = args;
  full.back() = "/dev/full";
  const mjarm::test::CliRun refused = run_cli(full, cwd);
  EXPECT_EQ(refused.exit_code, 1) << refused.err;
  EXPECT_NE(refused.err.find("'/dev/full': No space left on device"), std::string::npos)
      << refused.err;
}

TEST(FilesWritten, RenderAndWorkspaceOnAFullDiskKeepTheOldFile) {
  const fs::path cwd = scratch() / "files_written";
  fs::create_directories(cwd);
  expect_full_disk_keeps_the_old_file(cwd, {"render", "panda", "--out", "still.png"});
  expect_full_disk_keeps_the_old_file(
      cwd, {"workspace", "planar2", "--samples", "2000", "--out", "cloud.csv"});
}

// issue 29's bad-input matrix, gaps: the CSVs of `plan` and `traj` (about 2 000 and 2 500 rows)
// and a teleop session (about 2 KB: a limit of 1 KiB) on a full disk
TEST(FilesWritten, PlanTrajAndSessionFilesOnAFullDiskKeepTheOldFile) {
  const fs::path cwd = scratch() / "files_written_more";
  fs::remove_all(cwd);
  fs::create_directories(cwd);
  std::ofstream(cwd / "five.json")
      << R"({"waypoints": [{"position": [0.45, 0.0, 0.50]}, {"position": [0.45, 0.20, 0.40]},
  {"position": [0.35, 0.25, 0.35]}, {"position": [0.30, 0.10, 0.45]},
  {"position": [0.40, -0.15, 0.50]}]})";
  expect_full_disk_keeps_the_old_file(
      cwd, {"traj", "quintic", "--start", "0", "--target", "1", "--out", "traj.csv"});
  expect_full_disk_keeps_the_old_file(
      cwd, {"plan", "panda_torque", "--waypoints", "five.json", "--out", "plan.csv"});
  expect_full_disk_keeps_the_old_file(cwd, {"bimanual", "--record-session", "lift.session"}, 1024);
}

TEST(FilesWritten, AFifoThatNothingReadsIsAnErrorNotAHang) {
  const fs::path fifo = scratch() / "nobody_reads.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const mjarm::test::CliRun run =
      run_cli({"workspace", "planar2", "--samples", "10", "--out", fifo.string()});
  // refused with the output checks, before any sampling
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("a FIFO that nothing reads"), std::string::npos) << run.err;
  fs::remove(fifo);
}

}  // namespace
