#include "partreg/render/renderer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "gl_objects.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/render/mesh_proxy.hpp"

namespace partreg::render {

using detail::Buffer;
using detail::Framebuffer;
using detail::Program;
using detail::Renderbuffer;
using detail::VertexArray;

// What one mesh of the last frame left on the GPU, with the data it came from: what has not changed since
// is not converted or sent again (llvmpipe shares the two cores with everything else the app does).
struct MeshUpload {
  Buffer position_buffer, normal_buffer, color_buffer, index_buffer;
  core::Points vertices, given_normals;  // as in the MeshItem
  Eigen::Vector3d origin = Eigen::Vector3d::Constant(std::nan(""));
  core::Faces faces;
  Colors colors;  // per vertex, uniform colours spread out
  // Interactive frames of a dense mesh draw its proxy (built for `faces` when first needed) instead.
  std::unique_ptr<MeshProxy> proxy;
  core::Faces proxy_source;
  std::unique_ptr<MeshUpload> proxy_upload;
};

// A framebuffer the scene is drawn into.
struct DrawTarget {
  Framebuffer framebuffer;
  Renderbuffer color, depth;
};

// GL state of one renderer: programs, the framebuffers (the single-sampled `resolved` one holds every
// finished frame; full-quality frames with multisampling are drawn into `multisampled` and resolved into it),
// and the buffers reused from frame to frame.
struct Renderer::Gpu {
  Program splat_program, mesh_program, line_program;
  DrawTarget multisampled, resolved;
  bool drew_multisampled = false;  // the last frame waits in `multisampled` for its resolve
  int samples = 1;
  VertexArray vertex_array;
  Buffer positions, colors;  // splats and lines
  std::vector<MeshUpload> meshes;
};

namespace detail {

// What every pass needs to know about the frame. Geometry is drawn relative to `origin` (the scene's
// centre): floats keep their precision for data far from the origin (sensor frames, survey coordinates).
struct FrameState {
  Eigen::Vector3d origin;
  Eigen::Matrix4f view, projection;
  int width = 0, height = 0;
  bool multisampled = false;
  bool interactive = false;
};

}  // namespace detail

namespace {

using Frame = detail::FrameState;
using FloatRows = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;

void check_gl(const char* what) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", error);
  throw InputError(std::string("OpenGL error ") + code + " while " + what);
}

// Points `location` at the three floats per vertex in `buffer`.
void bind_attribute(GLuint buffer, GLuint location) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
}

// Sends rows as floats into `buffer`.
template <typename Rows>
void upload_rows(GLuint buffer, const Rows& rows) {
  const FloatRows data = rows.template cast<float>();
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(),
               GL_STREAM_DRAW);
}

// Uploads rows as a float attribute at `location`.
template <typename Rows>
void upload_attribute(GLuint buffer, GLuint location, const Rows& rows) {
  upload_rows(buffer, rows);
  bind_attribute(buffer, location);
}

template <typename Matrix>
bool same(const Matrix& a, const Matrix& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a == b;
}

// Per-element colours must come one per element.
void check_color_count(const Colors& colors, Eigen::Index count, const char* what) {
  if (colors.rows() != count)
    throw UsageError(std::string(what) + " has " + std::to_string(colors.rows()) + " colours for " +
                     std::to_string(count) + " elements");
}

// Per-element colours, or the uniform colour repeated.
Colors colors_or(const Colors& colors, const Color& color, Eigen::Index count, const char* what) {
  if (colors.rows() == 0) return color.transpose().replicate(count, 1);
  check_color_count(colors, count, what);
  return colors;
}

GLint uniform(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

void use_program(GLuint program, const Frame& frame) {
  glUseProgram(program);
  glUniformMatrix4fv(uniform(program, "view"), 1, GL_FALSE, frame.view.data());  // column-major
  glUniformMatrix4fv(uniform(program, "projection"), 1, GL_FALSE, frame.projection.data());
}

core::Points centred(const core::Points& points, const Eigen::Vector3d& origin) {
  return points.rowwise() - origin.transpose();
}

Frame make_frame(const Scene& scene, const Camera& camera, int width, int height) {
  const Bounds bounds = scene.bounds();
  Frame frame;
  frame.origin = bounds.empty() ? camera.target : bounds.centre();
  Camera shifted = camera;
  shifted.eye -= frame.origin;
  shifted.target -= frame.origin;
  Bounds shifted_bounds;
  if (!bounds.empty()) {
    shifted_bounds.extend(Eigen::Vector3d(bounds.min - frame.origin));
    shifted_bounds.extend(Eigen::Vector3d(bounds.max - frame.origin));
  }
  const Eigen::Vector2d clip = clip_range(shifted, shifted_bounds);
  frame.width = width;
  frame.height = height;
  frame.view = shifted.view_matrix();
  frame.projection = shifted.projection_matrix(static_cast<double>(width) / height, clip[0], clip[1]);
  return frame;
}

// About a third of the spacing of N points spread over a surface the size of the set, kept between 0.15%
// and 1% of its diagonal: sparse clouds still show their surface and dense ones stay crisp.
double automatic_radius(const PointSet& set) {
  Bounds bounds;
  bounds.extend(set.positions);
  const double diagonal = bounds.diagonal() > 0.0 ? bounds.diagonal() : 1.0;
  return diagonal * std::clamp(0.4 / std::sqrt(static_cast<double>(set.positions.rows())), 0.0015, 0.01);
}

Renderbuffer make_renderbuffer(GLenum format, int samples, int width, int height) {
  GLuint name = 0;
  glGenRenderbuffers(1, &name);
  glBindRenderbuffer(GL_RENDERBUFFER, name);
  // One sample is asked for as 0: a request for 1 may be rounded up to the smallest multisample count.
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, format, width, height);
  return Renderbuffer(name);
}

Framebuffer make_framebuffer(GLuint color, GLuint depth) {
  GLuint name = 0;
  glGenFramebuffers(1, &name);
  glBindFramebuffer(GL_FRAMEBUFFER, name);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
  if (depth != 0) glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw InputError("the renderer's framebuffer is incomplete on this OpenGL");
  return Framebuffer(name);
}

DrawTarget make_target(int samples, int width, int height) {
  DrawTarget target;
  target.depth = make_renderbuffer(GL_DEPTH_COMPONENT24, samples, width, height);
  target.color = make_renderbuffer(GL_RGBA8, samples, width, height);
  target.framebuffer = make_framebuffer(target.color.get(), target.depth.get());
  return target;
}

// Brings `upload` up to `item` (drawn relative to `origin`), sending only what changed since the last frame.
const MeshUpload& update_mesh_upload(MeshUpload& upload, const MeshItem& item,
                                     const Eigen::Vector3d& origin) {
  const core::Mesh& mesh = item.mesh;
  if (upload.position_buffer.get() == 0) {
    upload.position_buffer = detail::make_buffer();
    upload.normal_buffer = detail::make_buffer();
    upload.color_buffer = detail::make_buffer();
    upload.index_buffer = detail::make_buffer();
  }
  const bool faces_changed = !same(upload.faces, mesh.faces);
  if (faces_changed) {
    upload.faces = mesh.faces;
    const Eigen::Matrix<GLuint, Eigen::Dynamic, 3, Eigen::RowMajor> indices = mesh.faces.cast<GLuint>();
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, upload.index_buffer.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(GLuint)),
                 indices.data(), GL_STATIC_DRAW);
  }
  const bool vertices_changed = !same(upload.vertices, mesh.vertices);
  if (vertices_changed || upload.origin != origin) {
    upload.vertices = mesh.vertices;
    upload.origin = origin;
    upload_rows(upload.position_buffer.get(), centred(mesh.vertices, origin));
  }
  if (vertices_changed || faces_changed || !same(upload.given_normals, mesh.normals)) {
    upload.given_normals = mesh.normals;
    upload_rows(upload.normal_buffer.get(),
                mesh.normals.rows() == mesh.vertices.rows() ? mesh.normals : vertex_normals(mesh));
  }
  Colors colors = colors_or(item.vertex_colors, item.color, mesh.vertices.rows(), "a mesh");
  if (!same(upload.colors, colors)) {
    upload_rows(upload.color_buffer.get(), colors);
    upload.colors = std::move(colors);
  }
  return upload;
}

// The proxy of a dense mesh, as a mesh item of its own (each cluster takes its representative's colour),
// brought up to date in the proxy's upload.
const MeshUpload& update_proxy_upload(MeshUpload& full, const MeshItem& item, const Eigen::Vector3d& origin,
                                      int max_triangles) {
  // Rebuilt for new faces, and for a new vertex count (its clusters index the vertices it was built from).
  if (!full.proxy || !same(full.proxy_source, item.mesh.faces) ||
      full.proxy->vertex_count() != item.mesh.vertices.rows()) {
    full.proxy = std::make_unique<MeshProxy>(item.mesh, max_triangles);
    full.proxy_source = item.mesh.faces;
  }
  if (!full.proxy_upload) full.proxy_upload = std::make_unique<MeshUpload>();
  const MeshProxy& proxy = *full.proxy;
  MeshItem coarse;
  coarse.mesh.vertices = proxy.vertices(item.mesh.vertices);
  coarse.mesh.faces = proxy.faces();
  coarse.color = item.color;
  if (item.vertex_colors.rows() > 0) {
    check_color_count(item.vertex_colors, item.mesh.vertices.rows(), "a mesh");
    coarse.vertex_colors.resize(proxy.cluster_count(), 3);
    for (int c = 0; c < proxy.cluster_count(); ++c)
      coarse.vertex_colors.row(c) =
          item.vertex_colors.row(proxy.representatives()[static_cast<std::size_t>(c)]);
  }
  return update_mesh_upload(*full.proxy_upload, coarse, origin);
}

}  // namespace

Renderer::Renderer(const RenderSettings& settings) : settings_(settings), gpu_(std::make_unique<Gpu>()) {
  gpu_->splat_program = Program(compile_embedded_program("splat.vert", "", "splat.frag"));
  gpu_->mesh_program = Program(compile_embedded_program("mesh.vert", "", "mesh.frag"));
  gpu_->line_program = Program(compile_embedded_program("line.vert", "line.geom", "line.frag"));
  gpu_->vertex_array = detail::make_vertex_array();
  gpu_->positions = detail::make_buffer();
  gpu_->colors = detail::make_buffer();
  resize(settings.width, settings.height);
}

Renderer::~Renderer() = default;

void Renderer::resize(int width, int height) {
  GLint max_size = 0, max_samples = 1;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is outside 1.." + std::to_string(max_size) + " pixels");
  settings_.width = width;
  settings_.height = height;
  Gpu& gpu = *gpu_;
  gpu.samples = settings_.antialiasing == Antialiasing::multisample
                    ? std::clamp(settings_.samples, 1, std::max(1, static_cast<int>(max_samples)))
                    : 1;
  gpu.multisampled = gpu.samples > 1 ? make_target(gpu.samples, width, height) : DrawTarget();
  gpu.resolved = make_target(1, width, height);
  check_gl("creating the framebuffer");
}

void Renderer::draw(const Scene& scene, const Camera& camera, FrameQuality quality) {
  Gpu& gpu = *gpu_;
  Frame frame = make_frame(scene, camera, settings_.width, settings_.height);
  frame.interactive = quality == FrameQuality::interactive;
  frame.multisampled = gpu.drew_multisampled = gpu.samples > 1 && !frame.interactive;
  glBindFramebuffer(GL_FRAMEBUFFER, (frame.multisampled ? gpu.multisampled : gpu.resolved).framebuffer.get());
  glViewport(0, 0, frame.width, frame.height);
  if (settings_.background == Background::white)
    glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
  else
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);  // edges then come out premultiplied; read_pixels undoes it
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glBindVertexArray(gpu.vertex_array.get());
  if (gpu.meshes.size() != scene.meshes.size()) gpu.meshes.resize(scene.meshes.size());
  for (std::size_t slot = 0; slot < scene.meshes.size(); ++slot) draw_mesh(scene.meshes[slot], slot, frame);
  draw_splats(scene.point_sets, frame);
  draw_lines(scene.line_sets, frame);
  finish_frame();
  glBindVertexArray(0);
  check_gl("drawing");
}

void Renderer::draw_mesh(const MeshItem& item, std::size_t slot, const Frame& frame) {
  const core::Mesh& mesh = item.mesh;
  if (mesh.faces.rows() == 0) return;
  if (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= mesh.vertices.rows())
    throw UsageError("a mesh's faces index vertices it does not have");
  const GLuint program = gpu_->mesh_program.get();
  use_program(program, frame);
  MeshUpload& full = gpu_->meshes[slot];
  const bool coarse = frame.interactive && mesh.faces.rows() > settings_.interactive_triangles;
  const MeshUpload& upload =
      coarse ? update_proxy_upload(full, item, frame.origin, settings_.interactive_triangles)
             : update_mesh_upload(full, item, frame.origin);
  bind_attribute(upload.position_buffer.get(), 0);
  bind_attribute(upload.normal_buffer.get(), 1);
  bind_attribute(upload.color_buffer.get(), 2);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, upload.index_buffer.get());
  const auto count = static_cast<GLsizei>(upload.faces.size());
  glUniform1i(uniform(program, "flat_shading"), item.shading == Shading::flat ? 1 : 0);
  glUniform1i(uniform(program, "solid_color"), 0);
  const bool wireframe = item.wireframe && !coarse;  // a proxy's edges are not the mesh's
  if (wireframe) {
    // The surface is pushed back a little so that its own edges win the depth test.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
  }
  glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
  glDisable(GL_POLYGON_OFFSET_FILL);
  if (wireframe) {
    glUniform1i(uniform(program, "solid_color"), 1);
    glUniform3fv(uniform(program, "wire_color"), 1, item.wire_color.data());
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  glDisableVertexAttribArray(1);
  glDisableVertexAttribArray(2);
}

void Renderer::draw_splats(const std::vector<PointSet>& sets, const Frame& frame) {
  Gpu& gpu = *gpu_;
  const GLuint program = gpu.splat_program.get();
  use_program(program, frame);
  glUniform1f(uniform(program, "viewport_height"), static_cast<float>(frame.height));
  glUniform1i(uniform(program, "rim_coverage"), frame.multisampled ? 1 : 0);
  glEnable(GL_PROGRAM_POINT_SIZE);
  if (frame.multisampled) {
    // The splat's rim coverage (its alpha) becomes sample coverage; the stored alpha is then 1.
    glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glEnable(GL_SAMPLE_ALPHA_TO_ONE);
  }
  for (const PointSet& set : sets) {
    if (set.positions.rows() == 0) continue;
    upload_attribute(gpu.positions.get(), 0, centred(set.positions, frame.origin));
    upload_attribute(gpu.colors.get(), 1,
                     colors_or(set.colors, set.color, set.positions.rows(), "a point set"));
    const double radius = set.radius > 0.0 ? set.radius : automatic_radius(set);
    glUniform1f(uniform(program, "radius"), static_cast<float>(radius));
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(set.positions.rows()));
    glDisableVertexAttribArray(1);
  }
  glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  glDisable(GL_SAMPLE_ALPHA_TO_ONE);
}

void Renderer::draw_lines(const std::vector<LineSet>& sets, const Frame& frame) {
  Gpu& gpu = *gpu_;
  const GLuint program = gpu.line_program.get();
  use_program(program, frame);
  glUniform2f(uniform(program, "viewport_size"), static_cast<float>(frame.width),
              static_cast<float>(frame.height));
  for (const LineSet& set : sets) {
    const Eigen::Index count = set.starts.rows();
    if (count == 0) continue;
    if (set.ends.rows() != count) throw UsageError("a line set has unequal start and end counts");
    const Colors segment_colors = colors_or(set.colors, set.color, count, "a line set");
    core::Points ends(2 * count, 3);
    Colors end_colors(2 * count, 3);
    for (Eigen::Index i = 0; i < count; ++i) {
      ends.row(2 * i) = set.starts.row(i);
      ends.row(2 * i + 1) = set.ends.row(i);
      end_colors.row(2 * i) = end_colors.row(2 * i + 1) = segment_colors.row(i);
    }
    upload_attribute(gpu.positions.get(), 0, centred(ends, frame.origin));
    upload_attribute(gpu.colors.get(), 1, end_colors);
    glUniform1f(uniform(program, "width_pixels"), set.width_pixels);
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(2 * count));
    glDisableVertexAttribArray(1);
  }
}

// A multisampled frame is resolved into the single-sampled framebuffer; other frames were drawn there.
void Renderer::finish_frame() {
  if (!gpu_->drew_multisampled) return;
  const int width = settings_.width, height = settings_.height;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, gpu_->multisampled.framebuffer.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gpu_->resolved.framebuffer.get());
  glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

Image Renderer::read_pixels() const {
  const int width = settings_.width, height = settings_.height;
  Image image(width, height);
  std::vector<std::uint8_t> bottom_up(image.rgba.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, gpu_->resolved.framebuffer.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  check_gl("reading the image back");
  const std::size_t row_bytes = static_cast<std::size_t>(width) * 4;
  for (int y = 0; y < height; ++y)
    std::copy_n(bottom_up.data() + (height - 1 - y) * row_bytes, row_bytes,
                image.rgba.data() + y * row_bytes);
  // On the CPU: a full-screen pass costs llvmpipe several times more than this loop (measured).
  if (settings_.antialiasing == Antialiasing::edge) smooth_edges(image);
  if (settings_.background == Background::transparent)
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
      const int alpha = image.rgba[i + 3];
      if (alpha == 0 || alpha == 255) continue;
      for (int c = 0; c < 3; ++c)
        image.rgba[i + c] =
            static_cast<std::uint8_t>(std::min(255, (image.rgba[i + c] * 255 + alpha / 2) / alpha));
    }
  return image;
}

Image Renderer::render(const Scene& scene, const Camera& camera) {
  draw(scene, camera);
  return read_pixels();
}

unsigned Renderer::resolved_framebuffer() const { return gpu_->resolved.framebuffer.get(); }

}  // namespace partreg::render
