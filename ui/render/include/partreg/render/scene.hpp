#pragma once
/// \file
/// What the renderer draws: plain data, no GL. Point sets (round shaded splats), triangle meshes and line
/// sets, each with per-element or uniform colour, all in one scene frame (scene units).

#include <Eigen/Core>
#include <vector>

#include "partreg/core/types.hpp"
#include "partreg/render/camera.hpp"
#include "partreg/render/palette.hpp"

namespace partreg::render {

/// One sRGB colour per row, channels in [0, 1].
using Colors = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Points drawn as shaded round splats.
struct PointSet {
  core::Points positions;
  Colors colors;                  ///< one per point, or empty for `color`
  Color color = neutral_color();  ///< used when `colors` is empty
  double radius = 0.0;            ///< splat radius (scene units); 0 = from the point count and scene size
};

enum class Shading { smooth, flat };

/// A triangle mesh, lit from both sides.
struct MeshItem {
  core::Mesh mesh;                ///< normals are computed (area-weighted) when the mesh has none
  Colors vertex_colors;           ///< one per vertex, or empty for `color`
  Color color = neutral_color();  ///< used when `vertex_colors` is empty
  Shading shading = Shading::smooth;
  bool wireframe = false;  ///< draw the edges over the surface
  Color wire_color = Color(0.15f, 0.15f, 0.15f);
};

/// Straight segments of constant width in pixels: correspondences, axes, frame triads.
struct LineSet {
  core::Points starts;  ///< one segment per row of starts and ends
  core::Points ends;
  Colors colors;  ///< one per segment, or empty for `color`
  Color color = Color(0.2f, 0.2f, 0.2f);
  float width_pixels = 2.0f;  ///< line width (pixels of the output image)
};

struct Scene {
  std::vector<PointSet> point_sets;
  std::vector<MeshItem> meshes;
  std::vector<LineSet> line_sets;

  /// True when there is nothing to draw.
  bool empty() const;
  /// The box around every point, vertex and segment end.
  Bounds bounds() const;
  /// Every point, mesh vertex and segment end, one per row (what cameras are fitted to).
  core::Points all_points() const;
};

/// One colour per index from the part palette (negative index: grey).
Colors part_colors(const Eigen::VectorXi& part);

/// A frame drawn as three segments of `length` along its axes (columns of `rotation`), red, green, blue.
LineSet make_triad(const Eigen::Vector3d& position, const Eigen::Matrix3d& rotation, double length,
                   float width_pixels = 3.0f);

/// Segments from each row of `from` to the same row of `to` (same row count, else UsageError).
LineSet make_correspondences(const core::Points& from, const core::Points& to, Color color,
                             float width_pixels = 1.0f);

/// Per-vertex unit normals, area-weighted from the faces (zero-area neighbourhoods get +Z).
core::Points vertex_normals(const core::Mesh& mesh);

}  // namespace partreg::render
