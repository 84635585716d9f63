#include "folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

#include "mjarm/error.hpp"
#include "quoted_path.hpp"

namespace mjarm {
namespace {

// What the holder wrote into its lock file: "PID <n>, since <UTC time>" (empty when unreadable)
std::string holder_of(int fd) {
  char text[128] = {};
  const ssize_t n = ::pread(fd, text, sizeof(text) - 1, 0);
  std::string holder(text, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\0')) holder.pop_back();
  return holder;
}

// "PID <n>, since 2025-12-05T19:24:00Z"
std::string holder_text() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char when[32];
  std::strftime(when, sizeof(when), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return "PID " + std::to_string(::getpid()) + ", since " + when;
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& folder, const std::string& what)
    : file_(folder / kFileName) {
  // the holder removes the file while it still holds the lock: a writer that opened the old
  // file meanwhile finds it unlinked once it gets the lock, and tries again with a new one
  for (int attempt = 0;; ++attempt) {
    fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0)
      throw Error(what + " " + quoted(folder) + " is not writable: cannot create its lock file " +
                  quoted(file_) + ": " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string holder = holder_of(fd_);
      ::close(fd_);
      fd_ = -1;
      if (error != EWOULDBLOCK)
        throw Error("cannot lock the " + what + " " + quoted(folder) + " (" + quoted(file_) +
                    "): " + std::strerror(error));
      throw Error(what + " " + quoted(folder) + " is being written by another mjarm (" +
                  (holder.empty() ? std::string("PID unknown") : holder) + "; lock file " +
                  quoted(file_) + "); wait for it to end or choose another folder");
    }
    struct stat held {
    }, named{};
    if (::fstat(fd_, &held) == 0 && ::stat(file_.c_str(), &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino)
      break;
    ::close(fd_);  // the file we locked was removed by the writer before us: a new one
    fd_ = -1;
    if (attempt == 100)
      throw Error("cannot lock the " + what + " " + quoted(folder) + ": its lock file " +
                  quoted(file_) + " keeps being replaced");
  }
  const std::string holder = holder_text() + "\n";
  // best effort: the PID only helps the message of a writer refused later
  if (::ftruncate(fd_, 0) == 0) (void)!::pwrite(fd_, holder.data(), holder.size(), 0);
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  ::unlink(file_.c_str());  // while still locked (see the constructor)
  ::close(fd_);
}

}  // namespace mjarm
