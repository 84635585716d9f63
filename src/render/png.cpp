#include "mjarm/render/png.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "mjarm/file_writer.hpp"
#include "mjarm/error.hpp"
#include "quoted_path.hpp"

namespace mjarm {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// libpng reports errors through a callback that must not return; throwing a C++ exception out of
// it is unsafe across libpng's C frames, so the message is recorded and libpng's longjmp is used.
struct ErrorState {
  std::string message;
};

void on_png_error(png_structp png, png_const_charp message) {
  auto* state = static_cast<ErrorState*>(png_get_error_ptr(png));
  if (state != nullptr) state->message = message;
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// libpng's output goes through the FileWriter, which checks every write: the first failure
// stops libpng at once (on_png_error keeps the writer's message)
void on_png_write(png_structp png, png_bytep data, png_size_t size) {
  auto* file = static_cast<FileWriter*>(png_get_io_ptr(png));
  if (!file->write(data, size)) png_error(png, "write failed");
}

void on_png_flush(png_structp png) {
  auto* file = static_cast<FileWriter*>(png_get_io_ptr(png));
  if (!file->flush()) png_error(png, "write failed");
}

}  // namespace

void write_png(const Image& image, const std::filesystem::path& path) {
  // a new file beside the target, renamed over it once complete: never a truncated PNG
  FileWriter file(path, FileWriter::Mode::replace, "PNG");
  write_png(image, file);
  // a full disk may show only when the last bytes are flushed, synced or closed
  file.commit();
}

void write_png(const Image& image, FileWriter& file) {
  const std::filesystem::path& path = file.path();
  if (image.width <= 0 || image.height <= 0)
    throw Error("cannot write PNG " + quoted(path) + ": the image is empty (" +
                std::to_string(image.width) + "×" + std::to_string(image.height) + ")");
  if (image.rgb.size() != image.pixels() * 3)
    throw Error("cannot write PNG " + quoted(path) + ": the image holds " +
                std::to_string(image.rgb.size()) +
                " bytes, expected width·height·3 = " + std::to_string(image.pixels() * 3));
  ErrorState state;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_png_error, on_png_warning);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    throw Error("cannot write PNG " + quoted(path) + ": out of memory");
  }
  // the row pointers are made before setjmp so that no C++ object is live across the longjmp
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y)
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(image.at(0, y));
  if (setjmp(png_jmpbuf(png)) != 0) {
    // libpng jumped here from on_png_error; the uncommitted writer removes its temporary file
    png_destroy_write_struct(&png, &info);
    if (file.error() != 0) throw Error(file.failure());
    throw Error("cannot write PNG " + quoted(path) + ": " + state.message);
  }
  {
    png_set_write_fn(png, &file, on_png_write, on_png_flush);
    // fast zlib level: stills and frames are written often, size matters less than time
    png_set_compression_level(png, 3);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
  }
  png_destroy_write_struct(&png, &info);
}

Image read_png(const std::filesystem::path& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error("cannot read PNG " + quoted(path) + ": " + std::strerror(errno));
  png_byte signature[8] = {};
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
    throw Error("cannot read PNG " + quoted(path) + ": not a PNG file");

  ErrorState state;
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, on_png_error, on_png_warning);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw Error("cannot read PNG " + quoted(path) + ": out of memory");
  }
  Image image;
  std::vector<png_bytep> rows;
  if (setjmp(png_jmpbuf(png)) != 0) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw Error("cannot read PNG " + quoted(path) + ": " + state.message);
  }
  {
    png_init_io(png, file.get());
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    // normalise every colour type and bit depth to 8-bit RGB
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_strip_alpha(png);
    png_set_gray_to_rgb(png);
    png_read_update_info(png, info);
    image.width = static_cast<int>(png_get_image_width(png, info));
    image.height = static_cast<int>(png_get_image_height(png, info));
    if (png_get_rowbytes(png, info) != static_cast<std::size_t>(image.width) * 3)
      png_error(png, "unexpected row size after conversion to RGB");
    image.rgb.resize(image.pixels() * 3);
    rows.resize(static_cast<std::size_t>(image.height));
    for (int y = 0; y < image.height; ++y) rows[static_cast<std::size_t>(y)] = image.at(0, y);
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

}  // namespace mjarm
