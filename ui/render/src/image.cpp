#include "partreg/render/image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"

namespace partreg::render {
namespace {

void append_bytes(void* context, void* data, int size) {
  auto* bytes = static_cast<std::vector<unsigned char>*>(context);
  const auto* begin = static_cast<const unsigned char*>(data);
  bytes->insert(bytes->end(), begin, begin + size);
}

}  // namespace

Image::Image(int width_, int height_, Rgba8 fill) : width(width_), height(height_) {
  rgba.resize(static_cast<std::size_t>(std::max(width, 0)) * std::max(height, 0) * 4);
  for (std::size_t i = 0; i < rgba.size(); i += 4) std::copy(fill.begin(), fill.end(), rgba.begin() + i);
}

void blit(Image& canvas, const Image& source, int x, int y) {
  for (int row = std::max(0, -y); row < source.height && y + row < canvas.height; ++row)
    for (int column = std::max(0, -x); column < source.width && x + column < canvas.width; ++column) {
      const std::uint8_t* from = source.pixel(column, row);
      std::uint8_t* to = canvas.pixel(x + column, y + row);
      const int alpha = from[3];
      if (alpha == 255) {
        std::copy(from, from + 4, to);
        continue;
      }
      // "Over" with straight alpha.
      const int out_alpha = alpha + to[3] * (255 - alpha) / 255;
      for (int c = 0; c < 3; ++c)
        to[c] = static_cast<std::uint8_t>(
            out_alpha == 0 ? 0 : (from[c] * alpha + to[c] * to[3] * (255 - alpha) / 255) / out_alpha);
      to[3] = static_cast<std::uint8_t>(out_alpha);
    }
}

void smooth_edges(Image& image) {
  const int width = image.width, height = image.height;
  if (width < 3 || height < 3) return;
  std::vector<int> luma(static_cast<std::size_t>(width) * height);
  for (std::size_t i = 0; i < luma.size(); ++i)
    luma[i] = (77 * image.rgba[4 * i] + 150 * image.rgba[4 * i + 1] + 29 * image.rgba[4 * i + 2]) >> 8;
  const Image source = image;
  for (int y = 1; y + 1 < height; ++y)
    for (int x = 1; x + 1 < width; ++x) {
      const auto l = [&](int dx, int dy) { return luma[static_cast<std::size_t>(y + dy) * width + x + dx]; };
      const int c = l(0, 0), n = l(0, -1), s = l(0, 1), e = l(1, 0), w = l(-1, 0);
      const int low = std::min({c, n, s, e, w}), high = std::max({c, n, s, e, w});
      if (high - low < std::max(13, high / 8)) continue;
      // Sobel gradient (y down); the edge runs across it.
      const int gx = l(1, -1) + 2 * e + l(1, 1) - l(-1, -1) - 2 * w - l(-1, 1);
      const int gy = l(-1, 1) + 2 * s + l(1, 1) - l(-1, -1) - 2 * n - l(1, -1);
      const int ax = -gy, ay = gx;
      int sx = ax > 0 ? 1 : -1, sy = ay > 0 ? 1 : -1;
      if (std::abs(ax) * 5 > std::abs(ay) * 12) sy = 0;  // within 22.5 degrees of horizontal
      if (std::abs(ay) * 5 > std::abs(ax) * 12) sx = 0;  // within 22.5 degrees of vertical
      const std::uint8_t* forward = source.pixel(x + sx, y + sy);
      const std::uint8_t* backward = source.pixel(x - sx, y - sy);
      const std::uint8_t* centre = source.pixel(x, y);
      std::uint8_t* out = image.pixel(x, y);
      for (int k = 0; k < 4; ++k)
        out[k] = static_cast<std::uint8_t>((2 * centre[k] + forward[k] + backward[k] + 2) / 4);
    }
}

void write_png(const std::filesystem::path& path, const Image& image) {
  if (image.empty()) throw InputError("cannot write image " + path.string() + ": the image is empty");
  std::vector<unsigned char> bytes;
  if (!stbi_write_png_to_func(append_bytes, &bytes, image.width, image.height, 4, image.rgba.data(),
                              image.width * 4))
    throw InputError("cannot write image " + path.string() + ": PNG encoding failed");
  try {
    io::write_atomically(path, [&](const std::filesystem::path& temporary) {
      std::ofstream out(temporary, std::ios::binary);
      out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
      out.close();
      if (!out) throw InputError("cannot write image " + path.string() + ": " + std::strerror(errno));
    });
  } catch (const std::filesystem::filesystem_error& error) {
    throw InputError("cannot write image " + path.string() + ": " + error.code().message());
  }
}

Image read_png(const std::filesystem::path& path) {
  int width = 0, height = 0, channels = 0;
  unsigned char* data = stbi_load(path.string().c_str(), &width, &height, &channels, 4);
  if (!data) throw InputError("cannot read image " + path.string() + ": " + stbi_failure_reason());
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(data, data + static_cast<std::size_t>(width) * height * 4);
  stbi_image_free(data);
  return image;
}

}  // namespace partreg::render
