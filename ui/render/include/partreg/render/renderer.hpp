#pragma once
/// \file
/// The OpenGL 3.3 core renderer shared by the window and the headless figures. It draws a Scene into its
/// own multisampled framebuffer and resolves it; reading the pixels back is the same for every context.

#include <memory>
#include <string>
#include <vector>

#include "partreg/render/camera.hpp"
#include "partreg/render/image.hpp"
#include "partreg/render/scene.hpp"

namespace partreg::render {

enum class Background { white, transparent };

/// How edges are smoothed. Multisampling is the best looking and the slowest on software GL (llvmpipe
/// spends two to three times as long per frame); edge smoothing (smooth_edges on the read-back image)
/// costs a few milliseconds. The window blits the frame before read-back, so it shows edge smoothing as none.
enum class Antialiasing { multisample, edge, none };
}  // namespace partreg::render

template <>
struct partreg::core::EnumNames<partreg::render::Background> {
  using E = partreg::render::Background;
  static constexpr const char* what = "background";
  static constexpr std::array<std::pair<E, const char*>, 2> table{
      {{E::white, "white"}, {E::transparent, "transparent"}}};
};

template <>
struct partreg::core::EnumNames<partreg::render::Antialiasing> {
  using E = partreg::render::Antialiasing;
  static constexpr const char* what = "antialiasing";
  static constexpr std::array<std::pair<E, const char*>, 3> table{
      {{E::multisample, "msaa"}, {E::edge, "edge"}, {E::none, "none"}}};
};

namespace partreg::render {

/// What a frame may cost. Interactive frames (drawn while a slider, the camera or an animation moves) use one
/// sample per pixel and draw dense meshes as coarse proxies (MeshProxy): on llvmpipe a frame's cost grows
/// with the samples and the triangles, not the pixels. The frame drawn once things stop gets the full
/// quality.
enum class FrameQuality { full, interactive };

struct RenderSettings {
  int width = 1280;                                       ///< image width (pixels)
  int height = 960;                                       ///< image height (pixels)
  Antialiasing antialiasing = Antialiasing::multisample;  ///< see Antialiasing for the costs
  int samples = 4;  ///< samples per pixel with multisampling (capped by the GL's limit)
  Background background = Background::white;  ///< transparent: straight alpha in read_pixels()
  /// Meshes with more triangles are drawn as a proxy of at most this many in interactive frames.
  int interactive_triangles = 12000;
};

namespace detail {
struct FrameState;  // matrices and size of the frame being drawn (renderer.cpp)
}

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

  /// Draws `scene` seen by `camera` into the framebuffer. An empty scene gives the bare background. A mesh
  /// whose vertices, faces or colours equal those of the mesh drawn at the same position of the last frame's
  /// scene.meshes keeps what it has on the GPU: orbiting re-sends nothing, a slider move only positions
  /// and normals.
  void draw(const Scene& scene, const Camera& camera, FrameQuality quality = FrameQuality::full);
  /// The last drawn frame (resolved, edge-smoothed when asked), top row first.
  Image read_pixels() const;
  /// draw() then read_pixels().
  Image render(const Scene& scene, const Camera& camera);
  /// The GL name of the single-sampled framebuffer holding the resolved frame (a window blits from it).
  unsigned resolved_framebuffer() const;

 private:
  struct Gpu;
  void draw_mesh(const MeshItem& item, std::size_t slot, const detail::FrameState& frame);
  void draw_splats(const std::vector<PointSet>& sets, const detail::FrameState& frame);
  void draw_lines(const std::vector<LineSet>& sets, const detail::FrameState& frame);
  void finish_frame();
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
