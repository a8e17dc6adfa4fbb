#include "partreg/render/text.hpp"

#include <algorithm>
#include <vector>

// stb_easy_font: a public-domain 7-unit-tall bitmap font that hands out each glyph as quads. Its functions
// are static, so including it here keeps it private to this file.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace partreg::render {

void draw_text(Image& image, int x, int y, const std::string& text, int scale, Rgba8 color) {
  // Four vertices of 16 bytes (x, y, z, colour) per quad; 270 bytes a character is stb's own bound.
  std::vector<char> buffer(270 * (text.size() + 1));
  const int quads = stb_easy_font_print(0.0f, 0.0f, const_cast<char*>(text.c_str()), nullptr, buffer.data(),
                                        static_cast<int>(buffer.size()));
  const float* vertices = reinterpret_cast<const float*>(buffer.data());
  for (int q = 0; q < quads; ++q) {
    const float* quad = vertices + q * 16;  // x y z colour, four times: corners 0 and 2 are opposite
    const int x0 = x + static_cast<int>(quad[0]) * scale, y0 = y + static_cast<int>(quad[1]) * scale;
    const int x1 = x + static_cast<int>(quad[8]) * scale, y1 = y + static_cast<int>(quad[9]) * scale;
    for (int py = std::max(y0, 0); py < std::min(y1, image.height); ++py)
      for (int px = std::max(x0, 0); px < std::min(x1, image.width); ++px)
        std::copy(color.begin(), color.end(), image.pixel(px, py));
  }
}

int text_width(const std::string& text, int scale) {
  return stb_easy_font_width(const_cast<char*>(text.c_str())) * scale;
}

int text_line_height(int scale) { return 12 * scale; }

}  // namespace partreg::render
