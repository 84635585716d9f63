#pragma once
/// @file
/// Files for tests: a scratch directory, and whole-file reads.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

namespace mjarm::test {

/// A directory unique to this test process (several run at once under `ctest -j`), created on
/// first use and removed at exit.
inline std::filesystem::path scratch() {
  namespace fs = std::filesystem;
  struct Dir {
    fs::path path = fs::temp_directory_path() / ("mjarm_test_" + std::to_string(::getpid()));
    Dir() { fs::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

/// The whole content of @p path, byte for byte ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace mjarm::test
