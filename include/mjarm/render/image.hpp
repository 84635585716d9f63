#pragma once
/// @file
/// `Image`: an 8-bit RGB picture in memory, as the renderer produces and the PNG and video
/// writers consume it.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mjarm {

/// An 8-bit RGB image, rows top to bottom (row 0 is the top of the picture), pixels left to
/// right, 3 bytes (r, g, b) per pixel, no padding: byte (y·width + x)·3 + c is channel c of the
/// pixel in column x, row y.
struct Image {
  int width = 0;                    ///< [pixels]
  int height = 0;                   ///< [pixels]
  std::vector<std::uint8_t> rgb;    ///< width·height·3 bytes

  Image() = default;
  /// A black image of @p w × @p h pixels.
  Image(int w, int h)
      : width(w), height(h), rgb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3) {}

  /// Number of pixels.
  std::size_t pixels() const noexcept {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  /// The 3 bytes of the pixel at column @p x, row @p y (0 = top); unchecked.
  const std::uint8_t* at(int x, int y) const noexcept {
    return rgb.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                         static_cast<std::size_t>(x)) * 3;
  }
  /// Mutable access to the pixel at column @p x, row @p y (0 = top); unchecked.
  std::uint8_t* at(int x, int y) noexcept {
    return rgb.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                         static_cast<std::size_t>(x)) * 3;
  }
};

}  // namespace mjarm
