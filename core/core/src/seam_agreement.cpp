#include "seam_agreement.hpp"

#include <Eigen/Cholesky>

#include "partreg/core/gaussian_kernel.hpp"
#include "partreg/core/kdtree.hpp"
#include "partreg/core/sampling.hpp"

namespace partreg::core::detail {
namespace {

// Weight of the correction's smoothness (its kernel norm) against the seam targets: small, so the seam is
// met to a fraction of a percent of the diagonal, yet enough to keep the correction from oscillating
// between the fitted points (the part's kernel matrix is nearly singular at beta 0.3).
constexpr double kSmoothness = 1e-3;

// 1 within half the band (where the seam term and the seam gap read the fields), passing smoothly to 0 at
// the band's edge.
double seam_share(double distance, double band) { return smoothstep(2.0 * (1.0 - distance / band)); }

}  // namespace

PartSeam find_part_seam(const Points& canonical, const Eigen::VectorXi& canonical_part, int part,
                        const std::vector<int>& part_rows, double band) {
  PartSeam seam;
  seam.rows = part_rows;
  seam.own = static_cast<int>(part_rows.size());
  std::vector<int> other_rows;
  for (Eigen::Index i = 0; i < canonical_part.size(); ++i)
    if (canonical_part[i] != part) other_rows.push_back(static_cast<int>(i));
  seam.follow = Eigen::VectorXd::Zero(seam.own);
  seam.weight = Eigen::VectorXd::Ones(seam.own);
  if (other_rows.empty() || part_rows.empty() || !(band > 0.0)) return seam;

  const KdTree others(select_rows(canonical, other_rows));
  const KdTree own(select_rows(canonical, part_rows));
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
    seam.rows.push_back(row);
    follow.push_back(1.0);
    weight.push_back(seam_share(d, band));
  }
  seam.follow = Eigen::Map<const Eigen::VectorXd>(follow.data(), static_cast<Eigen::Index>(follow.size()));
  seam.weight = Eigen::Map<const Eigen::VectorXd>(weight.data(), static_cast<Eigen::Index>(weight.size()));
  return seam;
}

Points seam_agreeing_weights(const Points& canonical, const PartSeam& seam, const Points& part_weights,
                             const Points& holistic_weights, double beta) {
  if (!(seam.follow.maxCoeff() > 0.0)) return part_weights;
  const std::vector<int> own_rows(seam.rows.begin(), seam.rows.begin() + seam.own);
  const Points centres = select_rows(canonical, own_rows);
  const Points fitted = select_rows(canonical, seam.rows);
  const Eigen::MatrixXd K = gaussian_kernel(fitted, centres, beta);
  const Eigen::MatrixXd holistic = apply_kernel(fitted, canonical, holistic_weights, beta);
  // What the part's field must change by: towards the holistic field by each point's share of it.
  const Eigen::MatrixXd change = seam.follow.asDiagonal() * (holistic - K * part_weights);
  // Smallest smooth correction: min sum_j weight_j |K_j dW - change_j|^2 + s tr(dW' G dW) (+ a tiny ridge).
  const Eigen::MatrixXd weighted_K = seam.weight.asDiagonal() * K;
  const Eigen::MatrixXd G = K.topRows(seam.own);
  Eigen::MatrixXd normal = K.transpose() * weighted_K + kSmoothness * G;
  normal.diagonal().array() += 1e-9 * normal.diagonal().mean();
  const Eigen::MatrixXd correction = normal.ldlt().solve(weighted_K.transpose() * change);
  return part_weights + Points(correction);
}

}  // namespace partreg::core::detail
