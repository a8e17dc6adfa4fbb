#include "seam_agreement.hpp"

#include <Eigen/Cholesky>

#include "partreg/core/geometry/gaussian_kernel.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"

namespace partreg::core::detail {
namespace {

// Weight of the correction's smoothness (its kernel norm) against the seam targets: enough to keep the
// correction from oscillating between the fitted points (the part's kernel matrix is nearly singular at beta
// 0.3), small enough not to matter: the seam's residual comes from the kernel's width (kettles' seam gap at
// the training shapes: 0.63% at 1e-3, 0.57% at 1e-4 and 1e-5, 0.93% at 1e-2).
constexpr double kSmoothness = 1e-3;

// 1 within half the band (where the seam term and the seam gap read the fields), passing smoothly to 0 at
// the band's edge.
double seam_share(double distance, double band) { return smoothstep(2.0 * (1.0 - distance / band)); }

}  // namespace

SeamRefit::SeamRefit(const Points& canonical, const Eigen::VectorXi& canonical_part, int part,
                     const std::vector<int>& part_rows, double band, double beta)
    : canonical_(canonical), beta_(beta) {
  std::vector<int> other_rows;
  for (Eigen::Index i = 0; i < canonical_part.size(); ++i)
    if (canonical_part[i] != part) other_rows.push_back(static_cast<int>(i));
  if (other_rows.empty() || part_rows.empty() || !(band > 0.0)) return;

  const Points own_points = select_rows(canonical, part_rows);
  const KdTree others(select_rows(canonical, other_rows));
  const KdTree own(own_points);
  std::vector<int> rows = part_rows;
  std::vector<double> follow, weight;
  for (int row : part_rows) {
    const double d = std::sqrt(others.nearest(canonical.row(row).transpose()).second);
    follow.push_back(seam_share(d, band));
    weight.push_back(1.0);
  }
  // The neighbours' points near the part: there the part's field is what the seam term and the seam gap
  // read, so it must follow the holistic field too, weighed down towards the band's edge.
  for (int row : other_rows) {
    const double d = std::sqrt(own.nearest(canonical.row(row).transpose()).second);
    if (d >= band) continue;
    rows.push_back(row);
    follow.push_back(1.0);
    weight.push_back(seam_share(d, band));
  }
  follow_ = Eigen::Map<const Eigen::VectorXd>(follow.data(), static_cast<Eigen::Index>(follow.size()));
  if (!(follow_.maxCoeff() > 0.0)) return;  // no point near another part: nothing to refit
  weight_ = Eigen::Map<const Eigen::VectorXd>(weight.data(), static_cast<Eigen::Index>(weight.size()));
  fitted_ = select_rows(canonical, rows);
  kernel_ = gaussian_kernel(fitted_, own_points, beta);
  // Smallest smooth correction: min sum_j weight_j |K_j dW - change_j|^2 + s tr(dW' G dW) (+ a tiny ridge),
  // G the part's own kernel (the first rows of K).
  Eigen::MatrixXd normal = kernel_.transpose() * weight_.asDiagonal() * kernel_ +
                           kSmoothness * kernel_.topRows(static_cast<Eigen::Index>(part_rows.size()));
  normal.diagonal().array() += 1e-9 * normal.diagonal().mean();
  normal_.compute(normal);
}

Points SeamRefit::apply(const Points& part_weights, const Points& holistic_weights) const {
  if (fitted_.rows() == 0) return part_weights;
  const Eigen::MatrixXd holistic = apply_kernel(fitted_, canonical_, holistic_weights, beta_);
  // What the part's field must change by: towards the holistic field by each point's share of it.
  const Eigen::MatrixXd change = follow_.asDiagonal() * (holistic - kernel_ * part_weights);
  const Eigen::MatrixXd correction = normal_.solve(kernel_.transpose() * (weight_.asDiagonal() * change));
  return part_weights + Points(correction);
}

}  // namespace partreg::core::detail
