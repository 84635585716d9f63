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

// errno of a failed sync of @p dir, 0 when it reached the disk (or the file system cannot sync)
int sync_directory(const std::filesystem::path& dir) noexcept {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return errno;
  int error = ::fsync(fd) == 0 || errno == EINVAL || errno == EROFS ? 0 : errno;
  if (::close(fd) != 0 && error == 0 && errno != EINTR) error = errno;
  return error;
}

}  // namespace

StagingDir::StagingDir(const std::filesystem::path& directory) : directory_(directory) {
  if (directory.empty()) throw Error("recorder: the recording directory is empty");
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec || !std::filesystem::is_directory(directory)) {
    throw Error("recorder: cannot create recording directory '" + directory.string() +
                "': " + (ec ? ec.message() : std::string("exists and is not a directory")));
  }
  lock_ = std::make_unique<FolderLock>(directory, "recording folder");
  std::string pattern = (directory / ".partial-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    throw Error("recorder: recording directory '" + directory.string() +
                "' is not writable: " + std::strerror(errno));
  }
  staging_ = pattern;
}

void StagingDir::commit(const std::vector<std::string>& files, const std::string& marker) {
  struct Unlock {  // whatever happens below, the directory is no longer written after it
    StagingDir& dir;
    ~Unlock() { dir.unlock(); }
  } unlock{*this};
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
  if (const int error = sync_directory(directory_); error != 0) {
    throw Error("recorder: the recording was moved into '" + directory_.string() +
                "' but the folder could not be synced to disk: " + std::strerror(error));
  }
}

}  // namespace mjarm::sim_detail
