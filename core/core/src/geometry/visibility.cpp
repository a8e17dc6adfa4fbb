#include "visibility.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "partreg/core/geometry/kdtree.hpp"
#include "point_normals.hpp"

namespace partreg::core::detail {
namespace {

constexpr double kPixelsPerSpacing = 2.0;  // at the points' centre; nearer points splat over more pixels
constexpr int kLargestSplat = 8;           // pixels either side, for points much nearer than the centre
constexpr long kLargestSide = 1024;        // pixels a side: a viewpoint among the points asks for no more
constexpr double kSeenDepth = 2.0;         // spacings behind the front: seen
constexpr double kSeenDepthFacing = 6.0;   // spacings behind the front: seen when facing the viewpoint

double median_spacing(const Points& points) {
  if (points.rows() < 2) return 0.0;
  const KdTree tree(points);
  std::vector<double> gaps(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    gaps[static_cast<std::size_t>(i)] = std::sqrt(tree.nearest_k(points.row(i).transpose(), 2).back().second);
  const auto middle = gaps.begin() + static_cast<long>(gaps.size() / 2);
  std::nth_element(gaps.begin(), middle, gaps.end());
  return *middle;
}

}  // namespace

ViewSurface view_surface(const Points& points) { return {canonical_normals(points), median_spacing(points)}; }

ViewSurface restricted(const ViewSurface& surface, const std::vector<int>& rows, const Points& points) {
  ViewSurface part;
  part.normals.resize(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    part.normals.row(static_cast<Eigen::Index>(i)) = surface.normals.row(rows[i]);
  part.spacing = median_spacing(points);
  return part;
}

std::vector<bool> seen_rows(const Points& posed, const std::vector<bool>& facing, const Eigen::Vector3d& viewpoint,
                            double spacing) {
  const Eigen::Index count = posed.rows();
  if (count < 2 || !(spacing > 0.0)) return facing;
  // A perspective depth buffer from the viewpoint: angles from the axis through the points' centre.
  const Eigen::Vector3d centre = posed.colwise().mean().transpose();
  const double distance = (centre - viewpoint).norm();
  if (!(distance > spacing)) return facing;
  const Eigen::Vector3d axis = (centre - viewpoint) / distance;
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  double pixel = spacing / (kPixelsPerSpacing * distance);
  std::vector<double> depth(static_cast<std::size_t>(count));
  std::vector<double> x(static_cast<std::size_t>(count)), y(static_cast<std::size_t>(count));
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (Eigen::Index i = 0; i < count; ++i) {
    const Eigen::Vector3d ray = posed.row(i).transpose() - viewpoint;
    const auto k = static_cast<std::size_t>(i);
    depth[k] = ray.dot(axis);
    if (depth[k] <= spacing) continue;  // beside or behind the viewpoint: left to `facing`
    x[k] = ray.dot(u) / depth[k];
    y[k] = ray.dot(v) / depth[k];
    x0 = std::min(x0, x[k]), x1 = std::max(x1, x[k]), y0 = std::min(y0, y[k]), y1 = std::max(y1, y[k]);
  }
  if (!(x1 >= x0)) return facing;
  pixel = std::max(pixel, std::max(x1 - x0, y1 - y0) / static_cast<double>(kLargestSide));
  const long width = static_cast<long>((x1 - x0) / pixel) + 2 * kLargestSplat + 1;
  const long height = static_cast<long>((y1 - y0) / pixel) + 2 * kLargestSplat + 1;
  const auto cell = [&](std::size_t k) {
    return std::pair<long, long>(static_cast<long>((x[k] - x0) / pixel) + kLargestSplat,
                                 static_cast<long>((y[k] - y0) / pixel) + kLargestSplat);
  };
  std::vector<double> front(static_cast<std::size_t>(width * height), std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < depth.size(); ++k) {
    if (depth[k] <= spacing) continue;
    const auto [cx, cy] = cell(k);
    // One spacing wide wherever the point stands: a nearer point covers more pixels.
    const long reach = std::min<long>(kLargestSplat, static_cast<long>(std::ceil(kPixelsPerSpacing * distance /
                                                                                  depth[k])));
    for (long dy = -reach; dy <= reach; ++dy)
      for (long dx = -reach; dx <= reach; ++dx) {
        double& nearest = front[static_cast<std::size_t>((cy + dy) * width + (cx + dx))];
        nearest = std::min(nearest, depth[k]);
      }
  }
  std::vector<bool> seen = facing;
  for (std::size_t k = 0; k < depth.size(); ++k) {
    if (depth[k] <= spacing) continue;
    const auto [cx, cy] = cell(k);
    const double behind = depth[k] - front[static_cast<std::size_t>(cy * width + cx)];
    seen[k] = behind <= kSeenDepth * spacing || (facing[k] && behind <= kSeenDepthFacing * spacing);
  }
  return seen;
}

}  // namespace partreg::core::detail
