#include "mjarm/model/user_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <limits>

#include "mjarm/error.hpp"

namespace mjarm {

namespace {

std::string named(std::string_view what, const std::filesystem::path& path) {
  return std::string(what) + " '" + path.string() + "'";
}

std::string size_text(std::uintmax_t bytes) {
  if (bytes % (std::uintmax_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void throw_errno(std::string_view what, const std::filesystem::path& path, int error,
                              const char* doing) {
  switch (error) {
    case ENOENT:
      throw Error(named(what, path) + " does not exist");
    case ELOOP:
      throw Error(named(what, path) +
                  " is a symbolic link loop (ELOOP: too many levels of symbolic links)");
    case ENOTDIR:
      throw Error(named(what, path) +
                  " does not exist (a component of the path is not a directory)");
    default:
      throw Error(named(what, path) + " cannot be " + doing + ": " + std::strerror(error));
  }
}

// the checks shared by the path and the open descriptor
void check_stat(const struct stat& st, std::string_view what, const std::filesystem::path& path,
                std::uintmax_t max_bytes) {
  if (!S_ISREG(st.st_mode)) {
    throw Error(named(what, path) + " is " + kind_of(st.st_mode) + ", expected a regular file");
  }
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) {
    throw Error(named(what, path) + " is " + std::to_string(st.st_size) + " bytes, over the " +
                size_text(max_bytes) + " limit for a " + std::string(what));
  }
}

struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

bool has_extension(const std::filesystem::path& path, std::string_view extension) noexcept {
  const std::string ext = path.extension().string();
  return ext.size() == extension.size() &&
         std::equal(ext.begin(), ext.end(), extension.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) ==
                  std::tolower(static_cast<unsigned char>(b));
         });
}

void check_user_file(const std::filesystem::path& path, std::string_view what,
                     std::uintmax_t max_bytes) {
  if (path.empty()) throw Error(std::string(what) + " path is empty");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw_errno(what, path, errno, "examined");
  check_stat(st, what, path, max_bytes);
}

std::string read_user_file(const std::filesystem::path& path, std::string_view what,
                           std::uintmax_t max_bytes) {
  check_user_file(path, what, max_bytes);
  // non-blocking: a FIFO put in place after the check must not block the open
  const Fd file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) throw_errno(what, path, errno, "opened");
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw_errno(what, path, errno, "examined");
  check_stat(st, what, path, max_bytes);

  std::string text(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t used = 0;
  while (true) {
    // one byte of room past the limit tells a file that grew from one that ended
    if (used == text.size()) {
      if (text.size() > max_bytes) {
        throw Error(named(what, path) + " grew past the " + size_text(max_bytes) + " limit for a " +
                    std::string(what) + " while it was read");
      }
      text.resize(std::min<std::uintmax_t>(max_bytes + 1, text.size() + 65536));
    }
    const ssize_t n = ::read(file.fd, text.data() + used, text.size() - used);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw_errno(what, path, errno, "read");
    }
    if (n == 0) break;
    used += static_cast<std::size_t>(n);
  }
  text.resize(used);
  return text;
}

UserFileReader::UserFileReader(const std::filesystem::path& path, std::string_view what)
    : path_(path), what_(what) {
  constexpr auto kNoLimit = std::numeric_limits<std::uintmax_t>::max();
  check_user_file(path, what, kNoLimit);
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw_errno(what, path, errno, "opened");
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int error = errno;
    ::close(fd_);
    throw_errno(what, path, error, "examined");
  }
  try {
    check_stat(st, what, path, kNoLimit);
  } catch (...) {
    ::close(fd_);
    throw;
  }
  size_ = static_cast<std::uintmax_t>(st.st_size);
}

UserFileReader::~UserFileReader() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t UserFileReader::read(char* buffer, std::size_t size) {
  while (true) {
    const ssize_t n = ::read(fd_, buffer, size);
    if (n >= 0) return static_cast<std::size_t>(n);
    if (errno != EINTR) throw_errno(what_, path_, errno, "read");
  }
}

}  // namespace mjarm
