// Every fuzz target (fuzz/) on its seeds and on every input a fuzzing run found a defect with
// (fuzz/regressions/TARGET/): a target accepts each or refuses it with mjarm::Error, under the
// sanitized build of `make test`, with or without clang. The inputs are the files
// fuzz/corpora.txt names, as scripts/fuzz.sh stages them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"

namespace {

namespace fs = std::filesystem;
const fs::path kSourceDir = MJARM_SOURCE_DIR;

struct CorpusLine {
  std::string kind, target, path, extension;
};

std::vector<CorpusLine> corpus_table() {
  std::ifstream in(kSourceDir / "fuzz" / "corpora.txt");
  EXPECT_TRUE(in) << "cannot read fuzz/corpora.txt";
  std::vector<CorpusLine> lines;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    CorpusLine c;
    if (!(fields >> c.kind) || c.kind.front() == '#') continue;
    fields >> c.target >> c.path >> c.extension;
    lines.push_back(c);
  }
  return lines;
}

// the seeds of @p target, then its regression inputs, sorted within each folder
std::vector<fs::path> inputs_of(const std::string& target) {
  std::vector<fs::path> inputs;
  auto add_folder = [&](const fs::path& folder, const std::string& extension) {
    std::vector<fs::path> found;
    if (fs::is_directory(folder))
      for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.is_regular_file() && (extension.empty() || entry.path().extension() == extension))
          found.push_back(entry.path());
    std::sort(found.begin(), found.end());
    inputs.insert(inputs.end(), found.begin(), found.end());
  };
  for (const CorpusLine& c : corpus_table())
    if (c.kind == "seeds" && c.target == target) add_folder(kSourceDir / c.path, c.extension);
  add_folder(kSourceDir / "fuzz" / "regressions" / target, "");
  return inputs;
}

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class FuzzReplay : public ::testing::TestWithParam<mjarm::fuzz::FuzzTarget> {};

TEST_P(FuzzReplay, EverySeedAndRegressionIsAcceptedOrRefusedWithAnError) {
  const mjarm::fuzz::FuzzTarget target = GetParam();
  const std::vector<fs::path> inputs = inputs_of(target.name);
  ASSERT_FALSE(inputs.empty()) << "fuzz/corpora.txt names no seed for target " << target.name;
  for (const fs::path& input : inputs) {
    SCOPED_TRACE(input.string());
    const std::string bytes = bytes_of(input);
    // an exception other than mjarm::Error escapes the target and fails here, naming the input
    EXPECT_EQ(target.run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay, ::testing::ValuesIn(mjarm::fuzz::fuzz_targets()),
                         [](const auto& info) { return std::string(info.param.name); });

// scripts/fuzz.sh runs the targets corpora.txt lists, and this test the targets the code has
TEST(FuzzCorpora, ListEveryTargetAndOnlyThem) {
  std::set<std::string> listed, seeded, built;
  for (const CorpusLine& c : corpus_table()) {
    if (c.kind == "runs") listed.insert(c.target);
    if (c.kind == "seeds") seeded.insert(c.target);
  }
  for (const auto& target : mjarm::fuzz::fuzz_targets()) built.insert(target.name);
  EXPECT_EQ(listed, built);
  EXPECT_EQ(seeded, built);
}

}  // namespace
