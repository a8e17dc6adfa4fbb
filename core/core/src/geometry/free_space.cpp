#include "partreg/core/geometry/free_space.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

bool measured(float z) { return std::isfinite(z) && z > 0.0f; }

constexpr float kNone = std::numeric_limits<float>::infinity();

// The smallest of `image` (kNone where nothing was measured) within `radius` pixels, as a square window: a
// minimum over rows, then over columns.
Eigen::MatrixXf smallest_within(const Eigen::MatrixXf& image, int radius) {
  const auto pass = [radius](const Eigen::MatrixXf& in) {
    Eigen::MatrixXf out(in.rows(), in.cols());
    for (Eigen::Index c = 0; c < in.cols(); ++c)
      for (Eigen::Index r = 0; r < in.rows(); ++r) {
        const Eigen::Index first = std::max<Eigen::Index>(0, r - radius);
        const Eigen::Index last = std::min<Eigen::Index>(in.rows() - 1, r + radius);
        out(r, c) = in.col(c).segment(first, last - first + 1).minCoeff();
      }
    return out;
  };
  return pass(pass(image).transpose()).transpose();
}

}  // namespace

double FreeSpace::depth_at(int u, int v) const {
  // A lost pixel looks farther: a band of a silhouette lost at grazing angles is wider than the lateral
  // window, and the table just beyond it is not what the pixel's ray would have met.
  const int radius = measured(depth(v, u)) ? lateral_window : missing_window;
  float nearest = kNone;
  for (int y = std::max(0, v - radius); y <= std::min(height() - 1, v + radius); ++y)
    for (int x = std::max(0, u - radius); x <= std::min(width() - 1, u + radius); ++x)
      if (measured(depth(y, x))) nearest = std::min(nearest, depth(y, x));
  return nearest < kNone ? nearest : 0.0;
}

FreeSpace FreeSpace::prepared() const {
  FreeSpace out = *this;
  const Eigen::MatrixXf known = depth.unaryExpr([](float z) { return measured(z) ? z : kNone; });
  const Eigen::MatrixXf near = smallest_within(known, lateral_window),
                        far = smallest_within(known, missing_window);
  out.depth = known.binaryExpr(near, [](float own, float a) { return own < kNone ? a : kNone; })
                  .binaryExpr(far, [](float a, float b) { return a < kNone   ? a
                                                                 : b < kNone ? b
                                                                             : 0.0f; });
  out.lateral_window = out.missing_window = 0;
  return out;
}

double FreeSpace::violation(const Eigen::Vector3d& p) const {
  if (!(p.z() > 0.0)) return 0.0;  // behind the camera: never seen
  // Rounded to the nearest pixel centre; compared as reals first, so a point near the camera's plane cannot
  // overflow the rounding.
  const double u = std::round(fx * p.x() / p.z() + cx), v = std::round(fy * p.y() / p.z() + cy);
  if (!(u >= 0.0 && v >= 0.0 && u < width() && v < height())) return 0.0;
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
      lateral_window < 0 || missing_window < 0)
    throw InputError("free space: the noise, its multiple, the margin and the window must not be negative");
}

}  // namespace partreg::core
