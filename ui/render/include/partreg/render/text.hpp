#pragma once
/// \file
/// Titles on figure panels: a small bitmap font (stb_easy_font's glyph quads) drawn straight into an Image.

#include <string>

#include "partreg/render/image.hpp"

namespace partreg::render {

/// Draws printable ASCII `text` with its top-left corner at (x, y), each font unit `scale` pixels.
/// Lines are separated by '\n'; the font is about 7 units tall per line.
void draw_text(Image& image, int x, int y, const std::string& text, int scale, Rgba8 color = {0, 0, 0, 255});

/// Width in pixels of the widest line of `text` at `scale`.
int text_width(const std::string& text, int scale);

/// Height in pixels of one line of text at `scale`.
int text_line_height(int scale);

}  // namespace partreg::render
