// The refinement after the space fit (refinement.hpp): non-rigid CPD on landmark kernel centres, started at
// the fit, with only the observed points in the E-step and an anchor on the rest.
#include "partreg/core/registration/refinement.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <chrono>
#include <cmath>

#include "cpd/cpd_em.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "geometry/point_normals.hpp"
#include "space_solver.hpp"
#include "geometry/visibility.hpp"

namespace partreg::core {
namespace {

// Landmarks per unit area over beta^2: 0.5 puts kernel centres about 1.4 beta apart on a unit-diagonal
// object (surface area about 1), close enough for a smooth field, few enough that the K x K solve is cheap.
constexpr double kLandmarkDensity = 0.5;
// Kernel values below this are left out of the solve's G (a radius of 3.5 beta): each point then meets about
// 20 centres, not all K. Only the solve is truncated; the field is evaluated in full (apply_kernel).
constexpr double kTruncation = 2e-3;
// The smallest starting variance (normalised length squared): an exact fit would otherwise start at zero.
constexpr double kMinimumSigma2 = 1e-6;
// The smallest volume the outliers are spread over (normalised length cubed): a planar observation has none.
constexpr double kMinimumVolume = 1e-6;
// The largest outlier weight the stray share sets: past half, the data would be mostly noise and the space
// fit is the better answer.
constexpr double kMaximumOutlierWeight = 0.5;
// An observed point farther than kStrayDistance from every seen fitted point, with no more than
// kSurfaceNeighbours other observed points within kSurfaceRadius of it, is a stray: left out of the E-step. A
// far point with neighbours is surface the space missed, which the refinement is there to reach (a held-out
// bottle's full view: 3.2% refined, 5.0% with every far point left out). Uniform outliers stand alone: the
// paper's 20% in a box twice the object's size put about one other outlier within 0.05 of each. Both lengths
// are normalised and independent of the gate: widening the gate to reach what the space missed must not let
// the outliers in (Refinement.StraysFarFromTheFitDoNotPullIt failed with them at two gates of 0.1).
constexpr double kStrayDistance = 0.1;
constexpr double kSurfaceRadius = 0.05;
constexpr int kSurfaceNeighbours = 3;
// Fitted points whose normals blend into the direction a point may move in (refinement.hpp): about the
// points within one canonical spacing on either side.
constexpr int kNormalNeighbours = 6;

// The volume of the points' axis-aligned box, at least kMinimumVolume (a flat or degenerate set).
double bounding_box_volume(const Points& points) {
  const Eigen::RowVector3d extent = points.colwise().maxCoeff() - points.colwise().minCoeff();
  return std::max(kMinimumVolume, extent.prod());
}

void check(const Points& points, const char* name) {
  if (points.rows() < 10)
    throw InputError(std::string("the refinement needs at least 10 ") + name + " points, got " +
                     std::to_string(points.rows()));
  if (!points.allFinite())
    throw InputError(std::string("the refinement's ") + name + " points are not finite");
}

void check(const RefinementSettings& s) {
  if (!(s.beta > 0.0)) throw UsageError("the refinement's beta must be positive");
  if (!(s.lambda > 0.0)) throw UsageError("the refinement's lambda must be positive");
  if (!(s.anchor >= 0.0)) throw UsageError("the refinement's anchor must be zero or positive");
  if (!(s.gate > 0.0)) throw UsageError("the refinement's gate must be positive");
  if (!(s.outlier_weight >= 0.0 && s.outlier_weight < 1.0))
    throw UsageError("the refinement's outlier weight must be in [0, 1)");
  if (s.iterations < 1) throw UsageError("the refinement needs at least one iteration");
  if (!(s.noise_width >= 0.0)) throw UsageError("the refinement's noise width must be zero or positive");
}

// Which fitted points were observed: seen from the viewpoint (when known; the registration's own test,
// visible_rows, with the fitted points' own normals and spacing, already posed) and within the gate of an
// observed point. A normal facing the viewpoint alone was wrong inside concave shells (a bowl's or a mug's inner
// wall) and saw through the body.
std::vector<int> observed_rows(const Points& fitted, const detail::ViewSurface& surface, const KdTree& observed_tree,
                               const std::optional<Eigen::Vector3d>& viewpoint, double gate) {
  const std::vector<bool> seen = detail::visible_rows(fitted, surface, detail::Pose(), viewpoint);
  std::vector<int> rows;
  for (Eigen::Index m = 0; m < fitted.rows(); ++m)
    if (seen[static_cast<std::size_t>(m)] &&
        observed_tree.nearest(fitted.row(m).transpose()).second <= gate * gate)
      rows.push_back(static_cast<int>(m));
  return rows;
}

using SparseKernel = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// G(points, centres) without the values below kTruncation.
SparseKernel truncated_kernel(const Points& points, const Points& centres, double beta) {
  const KdTree tree(centres);
  const double radius = beta * std::sqrt(2.0 * std::log(1.0 / kTruncation));
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<std::pair<int, double>> near;
  for (Eigen::Index m = 0; m < points.rows(); ++m) {
    tree.radius(points.row(m).transpose(), radius, near);
    for (const auto& [l, d2] : near)
      entries.emplace_back(static_cast<int>(m), l, std::exp(-d2 / (2.0 * beta * beta)));
  }
  SparseKernel kernel(points.rows(), centres.rows());
  kernel.setFromTriplets(entries.begin(), entries.end());
  return kernel;
}

// G^T d(mass) G, dense (K x K), summed as the rows' outer products: a row meets a few dozen centres. Eigen's
// sparse-sparse product built a sparse result first and took over 40% of the refinement's time (perf,
// BM_KettleHolisticRefinedSerial; docs/benchmarks.md).
Eigen::MatrixXd weighted_gram(const SparseKernel& G, const Eigen::VectorXd& mass) {
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(G.cols(), G.cols());
  for (Eigen::Index m = 0; m < G.outerSize(); ++m)
    for (SparseKernel::InnerIterator a(G, m); a; ++a) {
      const double scaled = mass[m] * a.value();
      for (SparseKernel::InnerIterator b(G, m); b; ++b) gram(b.col(), a.col()) += scaled * b.value();
    }
  return gram;
}

// The rows of 0 .. count - 1 not in `rows` (ascending).
std::vector<int> other_rows(Eigen::Index count, const std::vector<int>& rows) {
  std::vector<bool> listed(static_cast<std::size_t>(count), false);
  for (int row : rows) listed[static_cast<std::size_t>(row)] = true;
  std::vector<int> others;
  for (Eigen::Index m = 0; m < count; ++m)
    if (!listed[static_cast<std::size_t>(m)]) others.push_back(static_cast<int>(m));
  return others;
}

}  // namespace

Points RefinementField::displacement_at(const Points& positions) const {
  if (empty()) return Points::Zero(positions.rows(), 3);
  return apply_kernel(positions, centres, weights, beta);
}

Points RefinementField::material_displacement_at(const Points& positions) const {
  const Points field = displacement_at(positions);
  if (empty() || surface.rows() == 0) return field;
  // The normal near p is a blend of its nearest fitted points' projectors n n^T (sign-free, and smooth
  // where the nearest point changes), weighted by a Gaussian of the distance on the scale of their spacing.
  const KdTree tree(surface);
  const int count = static_cast<int>(std::min<Eigen::Index>(kNormalNeighbours, surface.rows()));
  Points projected(positions.rows(), 3);
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    const std::vector<std::pair<int, double>> near = tree.nearest_k(positions.row(i).transpose(), count);
    const double scale2 = std::max(near.back().second, 1e-300);
    Eigen::Matrix3d projector = Eigen::Matrix3d::Zero();
    double total = 0.0;
    for (const auto& [row, squared] : near) {
      const double weight = std::exp(-squared / scale2);
      const Eigen::Vector3d n = surface_normals.row(row).transpose();
      projector += weight * n * n.transpose();
      total += weight;
    }
    projected.row(i) = (projector / total * field.row(i).transpose()).transpose();
  }
  return projected;
}

RefinementField RefinementField::transformed(double scale, const Eigen::Vector3d& offset) const {
  RefinementField field = *this;
  if (empty()) return field;
  field.centres = (centres * scale).rowwise() + offset.transpose();
  if (surface.rows() > 0) field.surface = (surface * scale).rowwise() + offset.transpose();
  field.weights = weights * scale;  // the kernel values do not change: distances and beta scale alike
  field.beta = beta * scale;
  return field;
}

RefinementField refine_fit(const Points& fitted, const Points& observed,
                           const std::optional<Eigen::Vector3d>& viewpoint,
                           const RefinementSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  check(settings);
  check(fitted, "fitted");
  check(observed, "observed");
  const KdTree observed_tree(observed);
  // The spacing is for the depth buffer: without a viewpoint only the normals are read (the noise below).
  const detail::ViewSurface surface =
      viewpoint ? detail::view_surface(fitted) : detail::ViewSurface{detail::canonical_normals(fitted), 0.0};
  const std::vector<int> seen = observed_rows(fitted, surface, observed_tree, viewpoint, settings.gate);
  RefinementField field;
  field.points = static_cast<int>(fitted.rows());
  field.observed = static_cast<int>(seen.size());
  if (seen.size() < 10) return field;  // nothing seen to refine towards: the space fit stands
  const Points fitted_seen = select_rows(fitted, seen);

  std::vector<int> unused_index;
  Eigen::VectorXd squared;  // from each observed point to the nearest seen fitted point
  KdTree(fitted_seen).nearest_all(observed, unused_index, squared);
  std::vector<int> near;
  std::vector<std::pair<int, double>> around;
  for (Eigen::Index n = 0; n < squared.size(); ++n) {
    if (squared[n] > kStrayDistance * kStrayDistance) {
      observed_tree.radius(observed.row(n).transpose(), kSurfaceRadius, around);
      if (static_cast<int>(around.size()) <= kSurfaceNeighbours) continue;  // itself and fewer than 3 others
    }
    near.push_back(static_cast<int>(n));
  }
  if (near.size() < 10) return field;
  const Points matched = select_rows(observed, near);
  field.matched = static_cast<int>(near.size());
  // Detail finer than the noise cannot be told from it: the kernel widens with the observation's noise, so a
  // noisy cloud is still refined, only more coarsely (letting the space fit stand alone above a thickness
  // limit was worse at every level of the paper's noise sweep, docs/registration.md). Every observed
  // point counts, the far ones too: at the paper's largest noise the points pushed beyond the
  // stray distance are the noise's tail (measured with only the matched ones: drills' full views 4.13 against
  // 3.70 at the largest level).
  field.noise = detail::observed_noise(observed, fitted, surface.normals);
  field.width = std::max(settings.beta, settings.noise_width * field.noise);
  const double beta = field.width;

  const auto count = std::min<Eigen::Index>(
      fitted.rows(),
      static_cast<Eigen::Index>(std::ceil(kLandmarkDensity / (beta * beta))));
  const Points centres = select_rows(fitted, farthest_point_indices(fitted, static_cast<std::size_t>(count)));
  const Eigen::MatrixXd G_centres = gaussian_kernel(centres, centres, beta);

  Points weights = Points::Zero(centres.rows(), 3);
  Points moved_seen = fitted_seen;
  detail::EmControl control;
  // The observation tells how many outliers it carries: the share the stray screen left out. Those that
  // passed it (with company, or within kStrayDistance) come from the same spread, so w is at least that share
  // (a fixed w must choose between real scans, best near 0, and the paper's outliers, alike from 0.01 to 0.2:
  // docs/registration.md).
  const double stray_share = 1.0 - static_cast<double>(near.size()) / static_cast<double>(observed.rows());
  field.outlier_weight = std::max(settings.outlier_weight, std::min(stray_share, kMaximumOutlierWeight));
  control.e_step.outlier_weight = field.outlier_weight;
  // Outliers spread over the matched points' box (docs/registration.md, "Strays"): with CPD's 1 / N a point
  // 4 or 5 sigma off still counted as surface, and the paper's box outliers that pass the stray screen
  // pulled the fit (kettles' full views at 20% outliers 1.79% with it, 1.54% over the box).
  control.e_step.outlier_volume = bounding_box_volume(matched);
  control.tolerance = 1e-5;
  control.max_iterations = settings.iterations;
  // The residual variance of the fit over the matched points, per axis (as CPD's sigma2 is).
  control.initial_sigma2 = std::max(kMinimumSigma2, squared(near).mean() / 3.0);
  // G(fitted, centres) apart by rows: the EM reads the observed rows only; the unobserved rows' share of the
  // normal equations changes only by its common weight (the anchor below), so it is summed once here.
  const SparseKernel G_seen = truncated_kernel(fitted_seen, centres, beta);
  const SparseKernel G_unseen =
      truncated_kernel(select_rows(fitted, other_rows(fitted.rows(), seen)), centres, beta);
  const Eigen::MatrixXd unseen_gram = weighted_gram(G_unseen, Eigen::VectorXd::Ones(G_unseen.rows()));
  const detail::EmOutcome outcome =
      detail::run_em(matched, moved_seen, control, [&](const detail::Expectation& e, double sigma2) {
        // Unobserved points pull towards zero displacement (the space's prediction) with the anchor's
        // weight, in units of an observed point's mean posterior mass.
        const double anchor = settings.anchor * e.Np / static_cast<double>(seen.size());
        const Points pull = e.PX - e.P1.asDiagonal() * fitted_seen;  // P X - d(P1) Y over the observed rows
        // (G^T d(mass) G + lambda sigma2 G_LL) W = G^T pull: the normal equations of CPD's objective with
        // the field on K centres (the motion-coherence term is the field's kernel norm W^T G_LL W); mass is
        // P1 on observed rows and the anchor on the others.
        Eigen::MatrixXd system = weighted_gram(G_seen, e.P1);
        system += anchor * unseen_gram + settings.lambda * sigma2 * G_centres;
        weights = system.ldlt().solve(G_seen.transpose() * pull);
        moved_seen = fitted_seen + Points(G_seen * weights);
        return detail::nonrigid_variance(e, matched, moved_seen);
      });
  field.centres = centres;
  field.weights = weights;
  field.beta = beta;  // frame units, as centres and weights (transformed() rescales it, not width)
  field.surface = fitted, field.surface_normals = surface.normals;
  field.iterations = outcome.iterations;
  const Eigen::VectorXd movement = field.displacement_at(fitted).rowwise().norm();
  field.mean_movement = movement.mean();
  field.max_movement = movement.maxCoeff();
  field.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return field;
}

}  // namespace partreg::core
