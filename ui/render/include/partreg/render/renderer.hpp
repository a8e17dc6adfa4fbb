#pragma once
/// \file
/// The OpenGL 3.3 core renderer shared by the window and the headless figures. It draws a Scene into its
/// own multisampled framebuffer and resolves it; reading the pixels back is the same for every context.

#include <memory>

#include "partreg/render/camera.hpp"
#include "partreg/render/image.hpp"
#include "partreg/render/scene.hpp"

namespace partreg::render {

enum class Background { white, transparent };

/// "white" | "transparent"; UsageError otherwise.
Background parse_background(const std::string& name);

struct RenderSettings {
  int width = 1280;  ///< image width (pixels)
  int height = 960;  ///< image height (pixels)
  int samples = 4;   ///< multisample antialiasing samples per pixel (1 = none; capped by the GL's limit)
  Background background = Background::white;
};

/// Draws scenes with the GL functions of the current context (see GlContext::make_current). Not copyable;
/// it owns GL objects of that context and must be destroyed while it is current.
class Renderer {
 public:
  /// Compiles the embedded shaders and creates the framebuffer. Throws InputError naming the shader and the
  /// first line of the compiler's log when a shader does not compile, or when the framebuffer is incomplete;
  /// UsageError for a size below 1 pixel or above the GL's limit.
  explicit Renderer(const RenderSettings& settings = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Changes the image size (recreates the framebuffer).
  void resize(int width, int height);
  const RenderSettings& settings() const { return settings_; }

  /// Draws `scene` seen by `camera` into the framebuffer. An empty scene gives the bare background.
  void draw(const Scene& scene, const Camera& camera);
  /// The last drawn frame (resolved), top row first.
  Image read_pixels() const;
  /// draw() then read_pixels().
  Image render(const Scene& scene, const Camera& camera);
  /// The GL name of the single-sampled framebuffer holding the resolved frame (a window blits from it).
  unsigned resolved_framebuffer() const;

 private:
  struct Gpu;
  RenderSettings settings_;
  std::unique_ptr<Gpu> gpu_;
};

/// Compiles and links a program from the embedded shader files `vertex`, `geometry` (may be empty) and
/// `fragment`, with `lighting.glsl` ahead of the fragment shader. Returns the GL program name. Throws
/// InputError naming the file on failure.
unsigned compile_embedded_program(const std::string& vertex, const std::string& geometry,
                                  const std::string& fragment);

/// Compiles and links a program from source texts (each without its #version line); `name` appears in the
/// error. Throws InputError ("shader NAME does not compile: <first line of the log>") on failure.
unsigned compile_program(const std::string& name, const std::string& vertex_source,
                         const std::string& geometry_source, const std::string& fragment_source);

}  // namespace partreg::render
