#pragma once
/// @file
/// `TiledRenderer`: several cameras of one state in one picture — a grid of tiles, one per
/// camera — for videos that show a run from several sides at once.

#include <mujoco/mujoco.h>

#include <vector>

#include "mjarm/model/robot.hpp"
#include "mjarm/render/camera.hpp"
#include "mjarm/render/image.hpp"
#include "mjarm/render/offscreen_renderer.hpp"

namespace mjarm {

/// The grid of a tiled picture: @p count tiles in rows of @p columns, left to right, top to
/// bottom. Default columns (0): all in one row up to 3 tiles, else ⌈√count⌉.
struct TileGrid {
  int columns = 1;
  int rows = 1;
  /// The grid for @p count tiles (≥ 1) and @p columns (0: the default).
  /// @throws Error when @p count < 1 or @p columns < 0.
  static TileGrid of(int count, int columns = 0);
};

/// Copies @p tile into @p out with its top-left corner at column @p x, row @p y (clipped to
/// @p out). Allocates nothing.
void blit(const Image& tile, Image& out, int x, int y) noexcept;

/// Renders each camera into its tile (tile_width × tile_height pixels) of one picture of
/// columns·tile_width × rows·tile_height pixels; unused tiles stay black. One
/// `OffscreenRenderer` draws every tile in turn, so the cost per picture is the cost of one
/// camera times the number of cameras.
class TiledRenderer {
 public:
  /// @throws Error for an empty camera list, a bad grid, or as `OffscreenRenderer` (sizes, no
  ///         OpenGL, markers).
  TiledRenderer(const Robot& robot, int tile_width, int tile_height,
                std::vector<CameraSpec> cameras, int columns = 0, RenderOptions options = {});

  /// Renders state @p data into @p out (resized when its size differs: reusing one `Image`
  /// allocates nothing per picture).
  /// @throws Error as `OffscreenRenderer::render` (an unknown camera names the model's).
  void render(const mjData& data, Image& out);
  Image render(const mjData& data);

  const std::vector<CameraSpec>& cameras() const noexcept { return cameras_; }
  const TileGrid& grid() const noexcept { return grid_; }
  int width() const noexcept { return grid_.columns * renderer_.width(); }  ///< [pixels]
  int height() const noexcept { return grid_.rows * renderer_.height(); }   ///< [pixels]

 private:
  OffscreenRenderer renderer_;
  std::vector<CameraSpec> cameras_;
  TileGrid grid_;
  Image tile_;
};

}  // namespace mjarm
