// PNG files: round trip, and clear errors for unwritable paths and bad images.

#include "mjarm/render/png.hpp"

#include <gtest/gtest.h>

#include <random>

#include "mjarm/error.hpp"
#include "render_test_support.hpp"
#include "support/file_size_limit.hpp"

namespace mjarm {
namespace {

TEST(Png, RoundTripKeepsEveryByteAndTheRowOrder) {
  Image image(37, 11);  // odd sizes: no row padding assumptions
  for (std::size_t i = 0; i < image.rgb.size(); ++i)
    image.rgb[i] = static_cast<std::uint8_t>((i * 7919) % 251);
  image.at(0, 0)[0] = 255;  // top-left marker
  const auto path = test::scratch() / "round.png";
  write_png(image, path);
  const Image back = read_png(path);
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 11);
  EXPECT_EQ(back.rgb, image.rgb);
  // the file is a real PNG: signature bytes
  const std::string bytes = test::slurp(path);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
}

TEST(Png, UnwritablePathNamesThePathAndTheReason) {
  Image image(4, 4);
  const auto missing = test::scratch() / "no_such_folder" / "x.png";
  try {
    write_png(image, missing);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
    EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  }
  // a folder is not a file
  EXPECT_THROW(write_png(image, test::scratch()), Error);
}

TEST(Png, AFullDiskLeavesTheOldFileAndNamesTheReason) {
  Image noise(96, 96);  // random bytes do not compress: ~27 KB of PNG
  std::mt19937 random(7);
  for (std::uint8_t& byte : noise.rgb) byte = static_cast<std::uint8_t>(random() >> 24);
  const auto dir = test::scratch() / "png_full";
  std::filesystem::create_directories(dir);
  const auto path = dir / "still.png";
  std::ofstream(path) << "old";
  const test::LimitedRun child = test::with_file_size_limit(4096, [&] {
    write_png(noise, path);
    return std::string("written");
  });
  ASSERT_EQ(child.exit_code, 1) << child.out;
  EXPECT_NE(child.err.find("cannot write PNG '" + path.string() + "'"), std::string::npos)
      << child.err;
  EXPECT_NE(child.err.find("File too large"), std::string::npos) << child.err;
  // never a truncated PNG: the old file as it was, and no temporary file beside it
  EXPECT_EQ(test::slurp(path), "old");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
  // with room, the same image replaces it whole
  write_png(noise, path);
  EXPECT_EQ(read_png(path).rgb, noise.rgb);
  try {
    write_png(noise, "/dev/full");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
  }
}

TEST(Png, ReplacingKeepsSymlinksAndPermissions) {
  namespace fs = std::filesystem;
  const auto dir = test::scratch() / "png_replace";
  fs::create_directories(dir);
  const auto real = dir / "real.png", link = dir / "link.png";
  std::ofstream(real) << "old";
  fs::permissions(real, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  fs::create_symlink("real.png", link);
  Image image(8, 6);
  image.at(3, 2)[1] = 200;
  write_png(image, link);
  // written through the link, as a plain write would: the link stays a link
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_png(real).rgb, image.rgb);
  EXPECT_EQ(fs::status(real).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(Png, EmptyOrInconsistentImagesAreErrors) {
  const auto path = test::scratch() / "bad.png";
  EXPECT_THROW(write_png(Image(), path), Error);
  Image broken(4, 4);
  broken.rgb.resize(10);
  EXPECT_THROW(write_png(broken, path), Error);
}

TEST(Png, ReadingSomethingElseIsAnError) {
  const auto path = test::scratch() / "not.png";
  std::ofstream(path) << "hello";
  EXPECT_THROW(read_png(path), Error);
  EXPECT_THROW(read_png(test::scratch() / "missing.png"), Error);
  // a truncated PNG
  Image image(64, 64);
  const auto good = test::scratch() / "good.png";
  write_png(image, good);
  const std::string bytes = test::slurp(good);
  const auto cut = test::scratch() / "cut.png";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_THROW(read_png(cut), Error);
}

}  // namespace
}  // namespace mjarm
