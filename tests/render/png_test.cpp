// PNG files: round trip, and clear errors for unwritable paths and bad images.

#include "mjarm/render/png.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "render_test_support.hpp"

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
