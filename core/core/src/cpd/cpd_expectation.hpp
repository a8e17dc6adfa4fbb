#pragma once
// The E-step shared by rigid, affine and non-rigid CPD (internal to partreg_core).
// It never stores the M x N posterior matrix: it accumulates the sums the M-steps need.

#include "partreg/core/types.hpp"

namespace partreg::core::detail {

/// Sufficient statistics of the posterior P (M x N, P_mn = p(source m | target n)).
struct Expectation {
  Eigen::VectorXd P1;                    ///< P 1: posterior mass per source point (M)
  Eigen::VectorXd Pt1;                   ///< P^T 1: posterior mass per target point (N)
  Points PX;                             ///< P X: posterior-weighted target per source point (M x 3)
  double Np = 0.0;                       ///< total mass, 1^T P 1
  double negative_log_likelihood = 0.0;  ///< up to a constant; its relative change stops EM
  double cell_edge = 0.0;                ///< edge of the cells the fast path merged points into (0: none)
};

/// How an E-step is computed.
struct EStepSettings {
  double outlier_weight = 0.1;  ///< w in [0, 1)
  /// The volume the outliers are spread over: their density is 1 / volume. 0 keeps CPD's 1 / N, which is a
  /// density per point, not per volume: at a small sigma it makes a point 5 sigma off more likely surface
  /// than outlier (docs/registration.md, "Strays"). The refinement sets it; CPD's own fits keep 1 / N.
  double outlier_volume = 0.0;
  int threads = 0;              ///< 0 = all cores
  /// Every source-target pair in double precision: the reference the fast path is tested against.
  bool exact = false;
  /// Fast path: kernel values below this are skipped (a radius of sqrt(2 ln(1/t)) sigma). CPD's settings
  /// set it (1e-4); this default serves the registration's refinement, which leaves it as it was.
  double truncation = 1e-8;
  /// Fast path: points sharing a voxel cell of this edge, in units of sigma, are merged into one weighted
  /// point at their centroid (on both sides). The kernel then changes by O(edge^2 / 12) relatively, and the
  /// first-order errors cancel in the M-steps' sums; 0 keeps every point on its own.
  double cell_size = 0.25;
};

/// One E-step for the current source positions `moved` against `target` with variance sigma2. The fast
/// path's work follows the points that matter: cells of a size tied to sigma (few while sigma is large)
/// and only the neighbours within the truncation radius (few once sigma is small).
Expectation expectation(const Points& moved, const Points& target, double sigma2,
                        const EStepSettings& settings);

/// The classic initial variance: mean squared distance over all source-target pairs, divided by 3.
double initial_sigma2(const Points& source, const Points& target);

/// `wanted` of the rows 0 .. count - 1, drawn at random without replacement (a fixed seed: the same rows in
/// every run and process), in increasing order; every row when count <= wanted. A random subset keeps the
/// density of the set, so EM's objective over it is an unbiased estimate of the objective over all points.
std::vector<int> random_rows(Eigen::Index count, Eigen::Index wanted);

/// Validates a point set for CPD, naming it in the message ("source", "target").
void check_cpd_points(const Points& points, const char* name);

/// Validates w and the tolerance.
void check_cpd_common(double outlier_weight, double tolerance, int max_iterations);

/// Validates the fast E-step's truncation (0, 1) and cell size [0, 1] sigma.
void check_fast_e_step(double truncation, double cell_size);

/// CPD's variance update for a moved source (non-rigid and affine: Myronenko & Song, Fig. 4) over the
/// E-step's points: sum P |t - y|^2 / (3 Np), from the E-step's sums.
double nonrigid_variance(const Expectation& e, const Points& target, const Points& moved);

}  // namespace partreg::core::detail
