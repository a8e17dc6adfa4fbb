#pragma once
/// \file
/// 8-bit RGBA images: what the renderer reads back, what figures are composed on, and PNG files.

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace partreg::render {

/// An RGBA colour, 8 bits per channel, straight (not premultiplied) alpha.
using Rgba8 = std::array<std::uint8_t, 4>;

/// An RGBA image, rows from top to bottom, 4 bytes per pixel, straight alpha.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes

  Image() = default;
  /// A width x height image filled with `fill` (opaque white by default).
  Image(int width, int height, Rgba8 fill = {255, 255, 255, 255});

  bool empty() const { return width == 0 || height == 0; }
  std::uint8_t* pixel(int x, int y) { return rgba.data() + 4 * (static_cast<std::size_t>(y) * width + x); }
  const std::uint8_t* pixel(int x, int y) const {
    return rgba.data() + 4 * (static_cast<std::size_t>(y) * width + x);
  }
};

/// Copies `source` into `canvas` with its top-left corner at (x, y), clipped to the canvas; source pixels
/// are blended over the canvas by their alpha.
void blit(Image& canvas, const Image& source, int x, int y);

/// Antialiasing after the fact: where the luminance of a pixel's 3x3 neighbourhood changes sharply, blends it
/// with its two neighbours along the edge (across the gradient, rounded to one of four directions), which
/// softens staircases; flat regions are left alone. Blends all four channels (premultiplied colours stay so).
void smooth_edges(Image& image);

/// Writes a PNG atomically. Throws InputError ("cannot write image out.png: ...") when it cannot.
void write_png(const std::filesystem::path& path, const Image& image);

/// Reads a PNG (any channel count, returned as RGBA). Throws InputError naming the file when it cannot.
Image read_png(const std::filesystem::path& path);

}  // namespace partreg::render
