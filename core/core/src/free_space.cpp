#include "partreg/core/free_space.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

bool measured(float z) { return std::isfinite(z) && z > 0.0f; }

}  // namespace

double FreeSpace::depth_at(int u, int v) const {
  const float own = depth(v, u);
  if (measured(own)) return own;
  // The smallest depth nearby: a lost pixel on the object's rim stands for the object, not the table behind.
  double nearest = 0.0;
  for (int y = std::max(0, v - missing_window); y <= std::min(height() - 1, v + missing_window); ++y)
    for (int x = std::max(0, u - missing_window); x <= std::min(width() - 1, u + missing_window); ++x) {
      const float z = depth(y, x);
      if (measured(z) && (nearest == 0.0 || z < nearest)) nearest = z;
    }
  return nearest;
}

double FreeSpace::violation(const Eigen::Vector3d& p) const {
  if (!(p.z() > 0.0)) return 0.0;  // behind the camera: never seen
  const long u = std::lround(fx * p.x() / p.z() + cx), v = std::lround(fy * p.y() / p.z() + cy);
  if (u < 0 || v < 0 || u >= width() || v >= height()) return 0.0;
  const double z = depth_at(static_cast<int>(u), static_cast<int>(v));
  if (z == 0.0) return std::numeric_limits<double>::infinity();
  return std::max(0.0, z - noise_multiple * sigma(z) - margin - p.z());
}

double FreeSpace::violation_share(const Points& points) const {
  if (points.rows() == 0) return 0.0;
  Eigen::Index violating = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (violation(T_camera_observed * Eigen::Vector3d(points.row(i).transpose())) > 0.0) ++violating;
  return static_cast<double>(violating) / static_cast<double>(points.rows());
}

void FreeSpace::validate() const {
  if (!(fx > 0.0) || !(fy > 0.0) || !std::isfinite(fx) || !std::isfinite(fy) || !std::isfinite(cx) ||
      !std::isfinite(cy))
    throw InputError("free space: the focal lengths must be finite and positive, the principal point finite");
  if (depth.size() == 0) throw InputError("free space: the depth image is empty");
  if ((depth.array() < 0.0f).any()) throw InputError("free space: the depth image holds negative depth");
  if (!(noise_offset >= 0.0) || !(noise_quadratic >= 0.0) || !(noise_multiple >= 0.0) || !(margin >= 0.0) ||
      missing_window < 0)
    throw InputError("free space: the noise, its multiple, the margin and the window must not be negative");
}

}  // namespace partreg::core
