#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "partreg/render/overlay.hpp"
#include "partreg/render/renderer.hpp"

namespace partreg::render {
namespace {

// Pixels (top-left origin) to clip space; the colour comes from the vertex times the texture.
const char* const kVertexShader = R"(
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 uv;
layout(location = 2) in vec4 color;
uniform vec2 frame_size;
out vec2 frag_uv;
out vec4 frag_color;
void main() {
  frag_uv = uv;
  frag_color = color;
  gl_Position = vec4(2.0 * position.x / frame_size.x - 1.0, 1.0 - 2.0 * position.y / frame_size.y, 0.0, 1.0);
}
)";

const char* const kFragmentShader = R"(
in vec2 frag_uv;
in vec4 frag_color;
uniform sampler2D overlay_texture;
out vec4 out_color;
void main() { out_color = frag_color * texture(overlay_texture, frag_uv); }
)";

}  // namespace

OverlayRenderer::OverlayRenderer() {
  program_ = compile_program("overlay", kVertexShader, "", kFragmentShader);
  glGenVertexArrays(1, &vertex_array_);
  glGenBuffers(1, &vertex_buffer_);
  glGenBuffers(1, &index_buffer_);
  glBindVertexArray(vertex_array_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex),
                        reinterpret_cast<void*>(offsetof(OverlayVertex, x)));
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex),
                        reinterpret_cast<void*>(offsetof(OverlayVertex, u)));
  glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(OverlayVertex),
                        reinterpret_cast<void*>(offsetof(OverlayVertex, rgba)));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);
  glBindVertexArray(0);
}

OverlayRenderer::~OverlayRenderer() {
  if (!textures_.empty()) glDeleteTextures(static_cast<GLsizei>(textures_.size()), textures_.data());
  glDeleteBuffers(1, &index_buffer_);
  glDeleteBuffers(1, &vertex_buffer_);
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteProgram(program_);
}

unsigned OverlayRenderer::create_texture(const std::uint8_t* rgba, int width, int height) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  textures_.push_back(texture);
  return texture;
}

void OverlayRenderer::draw(unsigned framebuffer, int width, int height,
                           const std::vector<OverlayList>& lists) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  // Straight alpha over an opaque frame; destination alpha accumulates like a "over" composite.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_SCISSOR_TEST);
  glUseProgram(program_);
  glUniform2f(glGetUniformLocation(program_, "frame_size"), static_cast<float>(width),
              static_cast<float>(height));
  glUniform1i(glGetUniformLocation(program_, "overlay_texture"), 0);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(vertex_array_);
  for (const OverlayList& list : lists) {
    if (list.draws.empty()) continue;
    glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(list.vertices.size() * sizeof(OverlayVertex)),
                 list.vertices.data(), GL_STREAM_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(list.indices.size() * sizeof(std::uint32_t)), list.indices.data(),
                 GL_STREAM_DRAW);
    for (const OverlayDraw& draw : list.draws) {
      // The scissor box has a bottom-left origin in GL.
      const int x0 = std::max(0, static_cast<int>(std::floor(draw.clip[0])));
      const int y0 = std::max(0, static_cast<int>(std::floor(draw.clip[1])));
      const int x1 = std::min(width, static_cast<int>(std::ceil(draw.clip[2])));
      const int y1 = std::min(height, static_cast<int>(std::ceil(draw.clip[3])));
      if (x1 <= x0 || y1 <= y0 || draw.index_count == 0) continue;
      glScissor(x0, height - y1, x1 - x0, y1 - y0);
      glBindTexture(GL_TEXTURE_2D, draw.texture);
      glDrawElementsBaseVertex(GL_TRIANGLES, static_cast<GLsizei>(draw.index_count), GL_UNSIGNED_INT,
                               reinterpret_cast<void*>(static_cast<std::size_t>(draw.first_index) * 4),
                               static_cast<GLint>(draw.vertex_offset));
    }
  }
  glBindVertexArray(0);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace partreg::render
