#include "replay_textures.hpp"

#include <zlib.h>

#include <algorithm>
#include <string>

#include "base64.hpp"
#include "mjarm/error.hpp"

namespace mjarm::web_detail {
namespace {

std::vector<unsigned char> deflate_rows(const std::vector<unsigned char>& pixels,
                                        std::size_t row_bytes) {
  // each byte minus the one above it (mod 256): the rows of a gradient or a checker become runs
  // of small numbers, which deflate compresses well
  std::vector<unsigned char> filtered(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    filtered[i] =
        static_cast<unsigned char>(pixels[i] - (i >= row_bytes ? pixels[i - row_bytes] : 0));
  }
  uLongf size = compressBound(static_cast<uLong>(filtered.size()));
  std::vector<unsigned char> out(size);
  // zlib's default level (6): on the bundled sky (256×1536, then 128×768) 0.04 s instead of
  // level 9's 0.84 s for 8 % more bytes (31,705 instead of 29,250 once halved)
  if (compress2(out.data(), &size, filtered.data(), static_cast<uLong>(filtered.size()),
                Z_DEFAULT_COMPRESSION) != Z_OK) {
    throw Error("replay-html: zlib could not compress a texture");
  }
  out.resize(size);
  return out;
}

// 2×2 means: a (w/2) × (h/2) picture
std::vector<unsigned char> halved(const std::vector<unsigned char>& pixels, int width, int height,
                                  int channels) {
  const int w = width / 2, h = height / 2;
  std::vector<unsigned char> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) *
                                 static_cast<std::size_t>(channels));
  auto at = [&](int x, int y, int k) {
    return static_cast<unsigned>(
        pixels[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                static_cast<std::size_t>(x)) *
                   static_cast<std::size_t>(channels) +
               static_cast<std::size_t>(k)]);
  };
  std::size_t i = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < channels; ++k) {
        const unsigned sum = at(2 * x, 2 * y, k) + at(2 * x + 1, 2 * y, k) +
                             at(2 * x, 2 * y + 1, k) + at(2 * x + 1, 2 * y + 1, k);
        out[i++] = static_cast<unsigned char>((sum + 2) / 4);
      }
  return out;
}

const char* texture_type_name(int type) {
  switch (type) {
    case mjTEXTURE_2D:
      return "2d";
    case mjTEXTURE_CUBE:
      return "cube";
    default:
      return "skybox";
  }
}

}  // namespace

EncodedTexture encode_texture(const unsigned char* pixels, int width, int height, int channels,
                              std::size_t budget) {
  EncodedTexture encoded;
  encoded.width = width;
  encoded.height = height;
  std::vector<unsigned char> kept(pixels, pixels + static_cast<std::size_t>(width) *
                                                       static_cast<std::size_t>(height) *
                                                       static_cast<std::size_t>(channels));
  // a cube strip (height 6·width) or a square face halves with its width; a 2D texture with both
  const bool strip = height == 6 * width;
  for (;;) {
    encoded.deflated = deflate_rows(
        kept, static_cast<std::size_t>(encoded.width) * static_cast<std::size_t>(channels));
    const int side = strip ? encoded.width : std::min(encoded.width, encoded.height);
    const bool even = encoded.width % 2 == 0 && encoded.height % 2 == 0;
    if (encoded.deflated.size() <= budget || !even || side / 2 < kSmallestSide) return encoded;
    kept = halved(kept, encoded.width, encoded.height, channels);
    encoded.width /= 2;
    encoded.height /= 2;
  }
}

std::vector<unsigned char> decode_texture(const std::vector<unsigned char>& deflated, int width,
                                          int height, int channels) {
  const std::size_t row = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  std::vector<unsigned char> pixels(row * static_cast<std::size_t>(height));
  uLongf size = static_cast<uLongf>(pixels.size());
  if (uncompress(pixels.data(), &size, deflated.data(), static_cast<uLong>(deflated.size())) !=
          Z_OK ||
      size != pixels.size()) {
    throw Error("replay-html: a texture's pixels do not inflate to its size");
  }
  for (std::size_t i = row; i < pixels.size(); ++i)
    pixels[i] = static_cast<unsigned char>(pixels[i] + pixels[i - row]);
  return pixels;
}

int ReplayTextures::use(int tex) {
  if (tex < 0 || tex >= m_.ntex) return -1;
  const int channels = m_.tex_nchannel[tex];
  if (channels != 1 && channels != 3 && channels != 4) return -1;
  const auto found = index_.find(tex);
  if (found != index_.end()) return found->second;
  const int width = m_.tex_width[tex], height = m_.tex_height[tex];
  const EncodedTexture encoded =
      encode_texture(m_.tex_data + m_.tex_adr[tex], width, height, channels);
  const int index = static_cast<int>(json_.size());
  json_.push_back({{"type", texture_type_name(m_.tex_type[tex])},
                   {"width", encoded.width},
                   {"height", encoded.height},
                   {"channels", channels},
                   {"source_width", width},
                   {"source_height", height},
                   {"data", base64(encoded.deflated.data(), encoded.deflated.size())}});
  index_.emplace(tex, index);
  return index;
}

int ReplayTextures::skybox() {
  for (int tex = 0; tex < m_.ntex; ++tex)
    if (m_.tex_type[tex] == mjTEXTURE_SKYBOX) return use(tex);
  return -1;
}

}  // namespace mjarm::web_detail
