#include "mjarm/render/tiled_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

#include "mjarm/error.hpp"

namespace mjarm {

TileGrid TileGrid::of(int count, int columns) {
  if (count < 1) throw Error("tiled picture: at least one camera is needed");
  if (columns < 0) throw Error("tiled picture: columns must be ≥ 0 (0: automatic)");
  TileGrid grid;
  grid.columns = columns > 0  ? std::min(columns, count)
                 : count <= 3 ? count
                              : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  grid.rows = (count + grid.columns - 1) / grid.columns;
  return grid;
}

void blit(const Image& tile, Image& out, int x, int y) noexcept {
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = std::min(x + tile.width, out.width), y1 = std::min(y + tile.height, out.height);
  if (x0 >= x1 || y0 >= y1) return;
  const std::size_t bytes = static_cast<std::size_t>(x1 - x0) * 3;
  for (int row = y0; row < y1; ++row) std::memcpy(out.at(x0, row), tile.at(x0 - x, row - y), bytes);
}

namespace {

std::vector<CameraSpec> checked_cameras(std::vector<CameraSpec> cameras) {
  if (cameras.empty()) throw Error("tiled picture: at least one camera is needed");
  return cameras;
}

}  // namespace

TiledRenderer::TiledRenderer(const Robot& robot, int tile_width, int tile_height,
                             std::vector<CameraSpec> cameras, int columns, RenderOptions options)
    : renderer_(robot, tile_width, tile_height, std::move(options)),
      cameras_(checked_cameras(std::move(cameras))),
      grid_(TileGrid::of(static_cast<int>(cameras_.size()), columns)) {}

void TiledRenderer::render(const mjData& data, Image& out) {
  if (out.width != width() || out.height != height()) out = Image(width(), height());
  for (std::size_t k = 0; k < cameras_.size(); ++k) {
    renderer_.render(data, cameras_[k], tile_);
    const int column = static_cast<int>(k) % grid_.columns;
    const int row = static_cast<int>(k) / grid_.columns;
    blit(tile_, out, column * renderer_.width(), row * renderer_.height());
  }
}

Image TiledRenderer::render(const mjData& data) {
  Image out(width(), height());
  render(data, out);
  return out;
}

}  // namespace mjarm
