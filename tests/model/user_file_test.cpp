#include "mjarm/model/user_file.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>

#include "mjarm/error.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

namespace fs = std::filesystem;
using test::error_of;

fs::path user_file_dir() {
  const fs::path dir = test::scratch() / "user_file";
  fs::create_directories(dir);
  return dir;
}

void expect_contains(const std::string& message, const std::string& part) {
  EXPECT_NE(message.find(part), std::string::npos) << message;
}

TEST(UserFile, ReadsARegularFileByteForByte) {
  const fs::path path = user_file_dir() / "bytes.bin";
  const std::string bytes("a\0b\nc", 5);
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(read_user_file(path, "model file"), bytes);
  const fs::path empty = user_file_dir() / "empty.xml";
  std::ofstream{empty};
  EXPECT_EQ(read_user_file(empty, "model file"), "");
}

TEST(UserFile, NamesWhatIsWrongWithThePath) {
  const fs::path dir = user_file_dir();
  expect_contains(error_of([&] { read_user_file(dir / "missing.xml", "model file"); }),
                  "model file '" + (dir / "missing.xml").string() + "' does not exist");
  expect_contains(error_of([&] { read_user_file(dir, "model file"); }),
                  "is a directory, expected a regular file");
  expect_contains(error_of([] { read_user_file("/dev/zero", "model file"); }),
                  "'/dev/zero' is a character device, expected a regular file");
  expect_contains(error_of([] { check_user_file("/dev/urandom", "mesh file"); }),
                  "mesh file '/dev/urandom' is a character device");
  // a loop is a loop, not a missing file
  fs::create_symlink("loop_b", dir / "loop_a");
  fs::create_symlink("loop_a", dir / "loop_b");
  const std::string loop = error_of([&] { read_user_file(dir / "loop_a", "model file"); });
  expect_contains(loop, "symbolic link loop (ELOOP");
  EXPECT_EQ(loop.find("does not exist"), std::string::npos) << loop;
  fs::create_symlink("nowhere.xml", dir / "dangling.xml");
  expect_contains(error_of([&] { read_user_file(dir / "dangling.xml", "model file"); }),
                  "does not exist");
  // a regular file used as a folder (made here: every test runs in its own process)
  std::ofstream(dir / "plain.txt") << "x";
  expect_contains(error_of([&] { read_user_file(dir / "plain.txt" / "x", "model file"); }),
                  "not a directory");
}

TEST(UserFile, RefusesAFifoWithoutBlocking) {
  const fs::path fifo = user_file_dir() / "pipe.xml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto read = std::async(std::launch::async,
                         [&] { return error_of([&] { read_user_file(fifo, "model file"); }); });
  if (read.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << "reading a FIFO blocked";
    // a writer unblocks the reader, so the test ends instead of hanging
    const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  }
  expect_contains(read.get(), "is a FIFO (named pipe), expected a regular file");
}

TEST(UserFile, RefusesFilesOverTheLimitAndNamesIt) {
  const fs::path path = user_file_dir() / "big.xml";
  std::ofstream(path) << std::string(1001, 'x');
  expect_contains(error_of([&] { read_user_file(path, "model file", 1000); }),
                  "is 1001 bytes, over the 1000 bytes limit for a model file");
  EXPECT_EQ(read_user_file(path, "model file", 1001).size(), 1001u);
  // the default limit, on a sparse file that costs no disk space
  fs::resize_file(path, kMaxTextFileBytes + 1);
  expect_contains(error_of([&] { check_user_file(path, "model file"); }),
                  "over the 64 MiB limit for a model file");
  EXPECT_NO_THROW(check_user_file(path, "mesh file", kMaxDataFileBytes));
}

}  // namespace
}  // namespace mjarm
