// Shader compilation: one clear error line naming the shader when the driver refuses it.
#include <glad/gl.h>

#include <string>
#include <string_view>
#include <vector>

#include "gl_objects.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/render/renderer.hpp"

namespace partreg::render {
namespace detail {
std::string_view embedded_shader(const std::string& name);  // generated from ui/shaders/
}

namespace {

std::string first_line(const std::string& text) {
  const std::size_t start = text.find_first_not_of(" \n\r\t");
  if (start == std::string::npos) return "(no log)";
  const std::size_t end = text.find_first_of("\n\r", start);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

detail::Shader compile_stage(GLenum stage, const std::string& name, const std::string& source) {
  detail::Shader shader(glCreateShader(stage));
  const std::string full = "#version 330 core\n" + source;
  const char* text = full.c_str();
  glShaderSource(shader.get(), 1, &text, nullptr);
  glCompileShader(shader.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    glGetShaderInfoLog(shader.get(), static_cast<GLsizei>(log.size()), nullptr, log.data());
    throw InputError("shader " + name + " does not compile: " + first_line(log));
  }
  return shader;
}

std::string embedded(const std::string& name) {
  const std::string_view text = detail::embedded_shader(name);
  if (text.empty()) throw InputError("shader " + name + " is not embedded in this build");
  return std::string(text);
}

struct Stage {
  GLenum type;
  std::string name;
  std::string source;  // empty: the stage is absent
};

GLuint link_program(const std::string& name, const std::vector<Stage>& stages) {
  std::vector<detail::Shader> shaders;
  for (const Stage& stage : stages)
    if (!stage.source.empty()) shaders.push_back(compile_stage(stage.type, stage.name, stage.source));
  detail::Program program(glCreateProgram());
  for (const detail::Shader& shader : shaders) glAttachShader(program.get(), shader.get());
  glLinkProgram(program.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(program.get(), static_cast<GLsizei>(log.size()), nullptr, log.data());
    throw InputError("shader program " + name + " does not link: " + first_line(log));
  }
  return program.release();
}

}  // namespace

unsigned compile_program(const std::string& name, const std::string& vertex_source,
                         const std::string& geometry_source, const std::string& fragment_source) {
  return link_program(name, {{GL_VERTEX_SHADER, name + " (vertex)", vertex_source},
                             {GL_GEOMETRY_SHADER, name + " (geometry)", geometry_source},
                             {GL_FRAGMENT_SHADER, name + " (fragment)", fragment_source}});
}

unsigned compile_embedded_program(const std::string& vertex, const std::string& geometry,
                                  const std::string& fragment) {
  // The fragment stages share lighting.glsl, put ahead of their own source (GLSL 3.30 has no #include).
  return link_program(vertex + "+" + fragment,
                      {{GL_VERTEX_SHADER, vertex, embedded(vertex)},
                       {GL_GEOMETRY_SHADER, geometry, geometry.empty() ? std::string() : embedded(geometry)},
                       {GL_FRAGMENT_SHADER, fragment, embedded("lighting.glsl") + embedded(fragment)}});
}

}  // namespace partreg::render
