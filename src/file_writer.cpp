#include "mjarm/file_writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "mjarm/error.hpp"
#include "quoted_path.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;

std::string cannot_write(const std::string& what, const fs::path& path) {
  return "cannot write " + (what.empty() ? std::string() : what + " ") + quoted(path) + ": ";
}

// fsync of a device, a pipe or a file system without it: nothing to sync, not a failure
bool sync_unsupported(int error) noexcept { return error == EINVAL || error == EROFS; }

// a distinct temporary name per writer, also across threads and processes
std::atomic<unsigned> temporary_counter{0};

}  // namespace

FileWriter::FileWriter(const fs::path& path, Mode mode, std::string what, std::size_t buffer_bytes)
    : path_(path), what_(std::move(what)), capacity_(std::max<std::size_t>(buffer_bytes, 1)) {
  if (path_.empty()) throw Error(cannot_write(what_, path_) + "the path is empty");
  struct stat info {};
  const bool exists = ::stat(path_.c_str(), &info) == 0;  // follows symlinks
  if (exists && S_ISDIR(info.st_mode))
    throw Error(cannot_write(what_, path_) + std::strerror(EISDIR));
  buffer_ = std::make_unique<char[]>(capacity_);
  if (mode == Mode::in_place || (exists && !S_ISREG(info.st_mode))) {
    // a FIFO nobody reads would block open() forever: without a reader it is an error (ENXIO)
    const bool fifo = exists && S_ISFIFO(info.st_mode);
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | (fifo ? O_NONBLOCK : 0),
                 0666);
    if (fd_ < 0) {
      const int error = errno;
      throw Error(cannot_write(what_, path_) + std::strerror(error) +
                  (fifo && error == ENXIO ? " (a FIFO that nothing reads)" : ""));
    }
    if (fifo) ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
    return;
  }
  // the temporary file lives beside the file it replaces (a symlink's target): rename is atomic
  // only within one file system
  target_ = path_;
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(path_, ec))) {
    const fs::path resolved = fs::canonical(path_, ec);
    if (!ec) target_ = resolved;
  }
  const fs::path folder = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  int error = 0;
  for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
    temporary_ = folder / ("." + target_.filename().string() + ".partial-" +
                           std::to_string(::getpid()) + "-" + std::to_string(temporary_counter++));
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    error = errno;
    if (fd_ < 0 && error != EEXIST) break;
  }
  if (fd_ < 0) {
    temporary_.clear();
    throw Error(cannot_write(what_, path_) + std::strerror(error));
  }
  // a replaced file keeps its permissions
  if (exists) ::fchmod(fd_, info.st_mode & 07777);
}

FileWriter::~FileWriter() {
  if (closed_) return;
  if (fd_ >= 0) ::close(fd_);
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
}

void FileWriter::fail(int error, const char* step) noexcept {
  if (error_ != 0) return;
  error_ = error != 0 ? error : EIO;
  step_ = step;
}

bool FileWriter::drain() noexcept {
  std::size_t done = 0;
  while (done < used_ && error_ == 0) {
    const ssize_t n = ::write(fd_, buffer_.get() + done, used_ - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
    } else if (n == 0) {
      fail(EIO, "");
    } else if (errno != EINTR) {
      fail(errno, "");
    }
  }
  used_ = 0;
  return error_ == 0;
}

bool FileWriter::write(const void* data, std::size_t n) noexcept {
  if (closed_) fail(EBADF, "");
  if (error_ != 0) return false;
  bytes_ += n;
  const char* bytes = static_cast<const char*>(data);
  while (n > 0) {
    if (used_ == capacity_ && !drain()) return false;
    const std::size_t k = std::min(n, capacity_ - used_);
    std::memcpy(buffer_.get() + used_, bytes, k);
    used_ += k;
    bytes += k;
    n -= k;
  }
  return true;
}

bool FileWriter::flush() noexcept {
  if (closed_ || error_ != 0) return error_ == 0;
  return drain();
}

bool FileWriter::close() noexcept {
  if (closed_) return error_ == 0;
  closed_ = true;
  drain();
  if (error_ == 0 && ::fsync(fd_) != 0 && !sync_unsupported(errno)) fail(errno, "sync");
  if (::close(fd_) != 0 && errno != EINTR) fail(errno, "close");
  fd_ = -1;
  if (temporary_.empty()) return error_ == 0;
  if (error_ == 0 && ::rename(temporary_.c_str(), target_.c_str()) != 0) fail(errno, "rename");
  if (error_ != 0) {
    ::unlink(temporary_.c_str());  // the target keeps its old content
    return false;
  }
  temporary_.clear();
  // the rename itself reaches the disk only with its folder
  const fs::path folder = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) {
    fail(errno, "folder");
  } else {
    if (::fsync(dir) != 0 && !sync_unsupported(errno)) fail(errno, "folder");
    ::close(dir);
  }
  return error_ == 0;
}

void FileWriter::commit() {
  if (!close()) throw Error(failure());
}

std::string FileWriter::failure() const {
  if (error_ == 0) return {};
  std::string message = cannot_write(what_, path_) + std::strerror(error_);
  const std::string_view step = step_;
  if (step == "sync") message += " (syncing it to disk)";
  if (step == "close") message += " (closing it)";
  if (step == "rename") message += " (moving the finished file into place)";
  if (step == "folder") message += " (syncing its folder; the new file is in place)";
  return message;
}

void write_file(const fs::path& path, std::string_view text, const std::string& what) {
  FileWriter writer(path, FileWriter::Mode::replace, what,
                    std::min<std::size_t>(text.size() + 1, 1 << 16));
  writer.write(text);
  writer.commit();
}

}  // namespace mjarm
