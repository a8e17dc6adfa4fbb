#pragma once
/// \file
/// 2D overlays drawn over a rendered frame: textured, vertex-coloured triangles in pixel coordinates with a
/// scissor rectangle per draw call. This is what a Dear ImGui draw list needs (the GUI converts its lists
/// into these), without the renderer depending on ImGui; the same pixels come out headless and in a window.

#include <array>
#include <cstdint>
#include <vector>

namespace partreg::render {

/// One vertex: position in pixels from the top-left corner, texture coordinates, and an RGBA colour packed
/// as ImGui packs it (red in the lowest byte). The layout matches ImDrawVert (20 bytes).
struct OverlayVertex {
  float x, y;
  float u, v;
  std::uint32_t rgba;
};

/// A run of indexed triangles drawn with one texture and one scissor rectangle.
struct OverlayDraw {
  unsigned texture = 0;                                  ///< from OverlayRenderer::create_texture
  std::array<float, 4> clip = {0.0f, 0.0f, 0.0f, 0.0f};  ///< x0, y0, x1, y1 in pixels (top-left origin)
  unsigned first_index = 0;
  unsigned index_count = 0;
  unsigned vertex_offset = 0;  ///< added to every index of this draw
};

/// A vertex buffer, an index buffer and the draws that use them.
struct OverlayList {
  std::vector<OverlayVertex> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<OverlayDraw> draws;
};

/// Draws overlay lists with the current GL context (create it while that context is current and destroy it
/// there too).
class OverlayRenderer {
 public:
  /// Compiles the overlay shader; InputError when it does not compile.
  OverlayRenderer();
  ~OverlayRenderer();
  OverlayRenderer(const OverlayRenderer&) = delete;
  OverlayRenderer& operator=(const OverlayRenderer&) = delete;

  /// Uploads an RGBA8 texture (rows top first) and returns its name for OverlayDraw::texture.
  unsigned create_texture(const std::uint8_t* rgba, int width, int height);

  /// Blends `lists` (straight alpha) over GL framebuffer `framebuffer` of width x height pixels, such as
  /// Renderer::resolved_framebuffer() after Renderer::draw().
  void draw(unsigned framebuffer, int width, int height, const std::vector<OverlayList>& lists);

 private:
  unsigned program_ = 0, vertex_array_ = 0, vertex_buffer_ = 0, index_buffer_ = 0;
  std::vector<unsigned> textures_;
};

}  // namespace partreg::render
