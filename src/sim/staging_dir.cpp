#include "staging_dir.hpp"

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "mjarm/error.hpp"

namespace mjarm::sim_detail {
namespace {

void sync_directory(const std::filesystem::path& dir) noexcept {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

StagingDir::StagingDir(const std::filesystem::path& directory) : directory_(directory) {
  if (directory.empty()) throw Error("recorder: the recording directory is empty");
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec || !std::filesystem::is_directory(directory)) {
    throw Error("recorder: cannot create recording directory '" + directory.string() + "': " +
                (ec ? ec.message() : std::string("exists and is not a directory")));
  }
  std::string pattern = (directory / ".partial-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    throw Error("recorder: recording directory '" + directory.string() + "' is not writable: " +
                std::strerror(errno));
  }
  staging_ = pattern;
}

void StagingDir::commit(const std::vector<std::string>& files, const std::string& marker) {
  // a reader must never pair an old summary with new rows: drop the stale marker first
  std::error_code ec;
  std::filesystem::remove(directory_ / marker, ec);
  std::vector<std::string> all = files;
  all.push_back(marker);
  for (const std::string& name : all) {
    const std::filesystem::path from = staging_ / name;
    const std::filesystem::path to = directory_ / name;
    if (std::rename(from.c_str(), to.c_str()) != 0) {
      throw Error("recorder: cannot move '" + from.string() + "' to '" + to.string() + "': " +
                  std::strerror(errno) + "; the recording stays in '" + staging_.string() + "'");
    }
  }
  std::filesystem::remove(staging_, ec);
  sync_directory(directory_);
}

}  // namespace mjarm::sim_detail
