// The scene cut's logic: which points go to PCL's steps (pcl_steps.cpp), and which cluster is the object.
#include "partreg/scene/segmentation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "pcl_steps.hpp"

namespace partreg::scene {
namespace {

// A pick farther than this from every cluster (m; pixels for a pixel pick) hits nothing.
constexpr double kPickReachMetres = 0.1;
constexpr double kPickReachPixels = 15.0;

core::Points rows_of(const core::Points& points, const std::vector<int>& rows) {
  core::Points out(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = points.row(rows[i]);
  return out;
}

double signed_distance(const Eigen::Vector4d& plane, const Eigen::Vector3d& point) {
  return plane.head<3>().dot(point) + plane[3];
}

void check_settings(const SegmentationSettings& s) {
  if (!(s.voxel_size >= 0 && s.plane_distance > 0 && s.cluster_tolerance > 0 && s.outlier_deviations > 0 &&
        s.min_plane_share >= 0 && s.min_plane_share <= 1 && s.plane_iterations > 0 &&
        s.outlier_neighbours > 0 && s.min_cluster_points > 0))
    throw UsageError("segmentation settings out of range (lengths must be positive, shares in [0, 1])");
}

void check_pick(const Pick& pick, const SceneView& view) {
  if (pick.pixel && pick.point) throw UsageError("pick a pixel or a point, not both");
  if (!pick.pixel) return;
  if (!view.intrinsics)
    throw UsageError("a pixel pick needs the camera's intrinsics (a depth image, or --intrinsics with a cloud)");
  if (!view.intrinsics->contains(pick.pixel->x(), pick.pixel->y()))
    throw UsageError("pick (" + std::to_string(pick.pixel->x()) + ", " + std::to_string(pick.pixel->y()) +
                     ") is outside the " + std::to_string(view.intrinsics->width) + "x" +
                     std::to_string(view.intrinsics->height) + " image");
}

// The support plane, oriented so that the camera (the origin) lies on its positive side. RANSAC runs on the
// measured points as the camera sampled them (every k-th, up to kPlaneSample), not on the voxel grid: a pixel
// grid weighs the near table over a far floor or wall that a voxel grid would favour for its larger area.
constexpr Eigen::Index kPlaneSample = 50000;

Eigen::Vector4d find_plane(const core::Points& measured, const SegmentationSettings& settings) {
  const Eigen::Index step = std::max<Eigen::Index>(1, measured.rows() / kPlaneSample);
  std::vector<int> rows;
  for (Eigen::Index i = 0; i < measured.rows(); i += step) rows.push_back(static_cast<int>(i));
  const core::Points sample = rows_of(measured, rows);
  detail::PlaneFit fit = detail::fit_plane(sample, settings);
  const double share = sample.rows() ? double(fit.inliers.size()) / double(sample.rows()) : 0.0;
  if (fit.inliers.empty() || share < settings.min_plane_share) {
    std::ostringstream what;
    what << "no support plane in the scene: the best plane holds " << fit.inliers.size() << " of "
         << sample.rows() << " points, below min_plane_share " << settings.min_plane_share;
    throw InputError(what.str());
  }
  if (fit.plane[3] < 0) fit.plane = -fit.plane;
  return fit.plane;
}

std::vector<Cluster> describe(const core::Points& points, const std::vector<std::vector<int>>& clusters) {
  std::vector<Cluster> out;
  for (const std::vector<int>& rows : clusters) {
    Cluster c;
    c.points = static_cast<int>(rows.size());
    c.centroid = rows_of(points, rows).colwise().mean().transpose();
    c.off_axis_degrees = std::acos(std::clamp(c.centroid.normalized().z(), -1.0, 1.0)) * 180.0 / M_PI;
    out.push_back(c);
  }
  return out;
}

// The cluster holding the point nearest `target` under `distance` (m or pixels), if within `reach`.
template <class Distance>
int nearest_cluster(const core::Points& points, const std::vector<std::vector<int>>& clusters,
                    const Distance& distance, double reach, double& best) {
  int chosen = -1;
  best = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < clusters.size(); ++c)
    for (int row : clusters[c]) {
      const double d = distance(Eigen::Vector3d(points.row(row).transpose()));
      if (d < best) best = d, chosen = static_cast<int>(c);
    }
  return best <= reach ? chosen : -1;
}

int choose(const core::Points& points, const std::vector<std::vector<int>>& clusters,
           const std::vector<Cluster>& described, const Pick& pick, const SceneView& view, std::string& why) {
  std::ostringstream text;
  double best = 0.0;
  int chosen = -1;
  if (pick.pixel) {
    const Intrinsics& k = *view.intrinsics;
    chosen = nearest_cluster(
        points, clusters, [&](const Eigen::Vector3d& p) { return (k.project(p) - *pick.pixel).norm(); },
        kPickReachPixels, best);
    if (chosen < 0) throw InputError("no cluster at pixel (" + std::to_string(pick.pixel->x()) + ", " +
                                     std::to_string(pick.pixel->y()) + ") (none within 15 pixels)");
    text << "at pixel (" << pick.pixel->x() << ", " << pick.pixel->y() << "), " << best << " px away";
  } else if (pick.point) {
    chosen = nearest_cluster(
        points, clusters, [&](const Eigen::Vector3d& p) { return (p - *pick.point).norm(); }, kPickReachMetres,
        best);
    if (chosen < 0) throw InputError("no cluster within 0.1 m of the picked point");
    text << "nearest the picked point (" << pick.point->transpose() << "), " << best << " m away";
  } else {
    for (std::size_t c = 0; c < described.size(); ++c)
      if (chosen < 0 || described[c].off_axis_degrees < described[chosen].off_axis_degrees)
        chosen = static_cast<int>(c);
    text << "nearest the image centre, " << described[chosen].off_axis_degrees << " degrees off the optical axis";
  }
  why = text.str();
  return chosen;
}

// The measured points (full resolution) whose nearest working point belongs to `rows` and lies within
// `reach`, above the plane.
CameraPoints full_resolution(const CameraPoints& measured, const core::Points& working,
                             const std::vector<int>& rows, const Eigen::Vector4d& plane, double above,
                             double reach) {
  const core::KdTree tree(rows_of(working, rows));
  std::vector<int> kept;
  for (Eigen::Index i = 0; i < measured.points.rows(); ++i) {
    const Eigen::Vector3d p = measured.points.row(i).transpose();
    if (signed_distance(plane, p) > above && tree.nearest(p).second <= reach * reach)
      kept.push_back(static_cast<int>(i));
  }
  CameraPoints out;
  out.points = rows_of(measured.points, kept);
  for (int i : kept) out.pixel.push_back(measured.pixel[i]);
  return out;
}

CameraPoints masked(const CameraPoints& measured, const PixelMask& mask) {
  std::vector<int> kept;
  for (std::size_t i = 0; i < measured.pixel.size(); ++i)
    if (measured.pixel[i] >= 0 && mask.selected[measured.pixel[i]]) kept.push_back(static_cast<int>(i));
  CameraPoints out;
  out.points = rows_of(measured.points, kept);
  for (int i : kept) out.pixel.push_back(measured.pixel[i]);
  return out;
}

}  // namespace

SceneCut cut_scene(const SceneView& view, const Pick& pick, const SegmentationSettings& settings) {
  check_settings(settings);
  check_pick(pick, view);
  if (view.measured.points.rows() < 3 * settings.min_cluster_points)
    throw InputError("the scene has " + std::to_string(view.measured.points.rows()) + " measured points");
  const core::Points grid = detail::voxelised(view.measured.points, settings.voxel_size);
  SceneCut cut;
  cut.free_space = free_space_of(view);
  const std::vector<int> kept = detail::inlier_rows(grid, settings);
  cut.outliers_removed = static_cast<int>(grid.rows()) - static_cast<int>(kept.size());
  const core::Points working = rows_of(grid, kept);
  cut.plane = find_plane(view.measured.points, settings);
  cut.up = cut.plane.head<3>();
  std::vector<int> on_plane;
  for (Eigen::Index i = 0; i < working.rows(); ++i)
    if (std::abs(signed_distance(cut.plane, working.row(i).transpose())) <= settings.plane_distance)
      on_plane.push_back(static_cast<int>(i));
  cut.plane_points = rows_of(working, on_plane);
  if (view.mask) {
    cut.object = masked(view.measured, *view.mask);
    cut.choice = "the mask's pixels";
    if (cut.object.points.rows() == 0) throw InputError("the mask selects no measured pixel");
    return cut;
  }
  std::vector<int> above;
  for (Eigen::Index i = 0; i < working.rows(); ++i)
    if (signed_distance(cut.plane, working.row(i).transpose()) > settings.plane_distance)
      above.push_back(static_cast<int>(i));
  const std::vector<std::vector<int>> clusters = detail::euclidean_clusters(working, above, settings);
  if (clusters.empty())
    throw InputError("no cluster of at least " + std::to_string(settings.min_cluster_points) +
                     " points above the support plane");
  cut.clusters = describe(working, clusters);
  cut.chosen = choose(working, clusters, cut.clusters, pick, view, cut.choice);
  const double reach = std::max(settings.voxel_size, settings.cluster_tolerance / 2);
  cut.object = full_resolution(view.measured, working, clusters[cut.chosen], cut.plane, settings.plane_distance,
                               reach);
  return cut;
}

}  // namespace partreg::scene
