#pragma once
/// @file
/// Paths a reader of user files must refuse with a clear error (issue 16, item 7): a FIFO, a
/// character device, a directory, a symbolic link loop and a file over the size limit; and the
/// error a reader gives for one of them, without hanging the test when the reader blocks.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <string>
#include <vector>

#include "support/error_message.hpp"

namespace mjarm::test {

/// A path and the words the reader's error must hold for it.
struct UnreadablePath {
  std::filesystem::path path;
  std::string expected;
};

/// Makes, in @p dir, files named @p stem + ".fifo" (a FIFO), ".loop" (a symbolic link loop),
/// ".dir" (a directory) and ".big" (a sparse regular file of @p too_big bytes), each with
/// @p extension; and names /dev/null (a character device that ends at once).
inline std::vector<UnreadablePath> unreadable_paths(const std::filesystem::path& dir,
                                                    const std::string& stem,
                                                    const std::string& extension,
                                                    std::uintmax_t too_big) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const fs::path fifo = dir / (stem + "_fifo" + extension);
  const fs::path loop = dir / (stem + "_loop" + extension);
  const fs::path other = dir / (stem + "_other" + extension);
  const fs::path folder = dir / (stem + "_dir" + extension);
  const fs::path big = dir / (stem + "_big" + extension);
  std::error_code ec;
  for (const fs::path& p : {fifo, loop, other, big}) fs::remove(p, ec);
  EXPECT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink(other.filename(), loop);
  fs::create_symlink(loop.filename(), other);
  fs::create_directories(folder);
  {
    const int fd = ::open(big.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    EXPECT_GE(fd, 0);
    if (fd >= 0) {
      EXPECT_EQ(::ftruncate(fd, static_cast<off_t>(too_big)), 0);  // sparse: no disk space
      ::close(fd);
    }
  }
  return {{fifo, "is a FIFO (named pipe), expected a regular file"},
          {"/dev/null", "is a character device, expected a regular file"},
          {folder, "is a directory, expected a regular file"},
          {loop, "is a symbolic link loop (ELOOP"},
          {big, "limit"}};
}

/// The message of the Error @p read throws for @p path; when it blocks for 10 s (a FIFO opened
/// for reading), a test failure, and a writer opened and closed on the FIFO so the reader ends.
template <class F>
std::string error_without_blocking(const std::filesystem::path& path, F&& read) {
  auto result = std::async(std::launch::async, [&] { return error_of([&] { read(path); }); });
  if (result.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << "reading " << path << " blocked";
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  }
  return result.get();
}

}  // namespace mjarm::test
