#pragma once
/// @file
/// The textures a replay page draws, each embedded once however many geoms use it: 2D textures
/// (on planes, boxes, meshes, … as MuJoCo maps them), cube textures, and the skybox. The pixels
/// are sent compressed: each row as its difference from the row above (PNG's "up" filter), then
/// deflated (zlib), then base64; the page inflates them with the browser's DecompressionStream.
/// A texture whose compressed pixels exceed kTextureBudget is halved (2×2 mean) until it fits or
/// a side would fall below kSmallestSide (a skybox's smooth gradient loses nothing visible; a
/// checker's cells keep their edges at the sizes the bundled floors use). The page's JSON states
/// both sizes.

#include <mujoco/mujoco.h>

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

namespace mjarm::web_detail {

/// Bytes of compressed pixels above which a texture is halved.
inline constexpr std::size_t kTextureBudget = 48 * 1024;
/// A face's side (a 2D texture's width or height) below which no texture is halved.
inline constexpr int kSmallestSide = 16;

/// The pixels of one texture as the page receives them: kept size and compressed bytes.
struct EncodedTexture {
  int width = 0, height = 0;  ///< kept size (a cube: width × 6·width, or one face repeated)
  std::vector<unsigned char> deflated;
};

/// @p pixels (@p width × @p height, @p channels bytes each, row 0 first): "up"-filtered and
/// deflated, halved while over @p budget and both sides stay ≥ kSmallestSide (and even).
/// A cube's faces, stacked, are halved with it: a 2×2 block never spans two faces of even side.
/// @throws Error when zlib fails.
EncodedTexture encode_texture(const unsigned char* pixels, int width, int height, int channels,
                              std::size_t budget = kTextureBudget);

/// Undoes encode_texture's filter and deflate (for tests): the kept pixels, row 0 first.
std::vector<unsigned char> decode_texture(const std::vector<unsigned char>& deflated, int width,
                                          int height, int channels);

class ReplayTextures {
 public:
  explicit ReplayTextures(const mjModel& m) : m_(m) {}

  /// The index in json() of model texture @p tex, embedded on first use; -1 when the page cannot
  /// draw it (a channel count other than 1, 3 or 4).
  int use(int tex);

  /// The index in json() of the model's first skybox texture (MuJoCo draws the first), -1 when
  /// it has none.
  int skybox();

  /// [{type: "2d" | "cube" | "skybox", width, height, channels, source_width, source_height,
  ///   data: base64 of the deflated, filtered pixels}]
  const nlohmann::json& json() const { return json_; }

 private:
  const mjModel& m_;
  nlohmann::json json_ = nlohmann::json::array();
  std::map<int, int> index_;  // model texture id → index in json_
};

}  // namespace mjarm::web_detail
