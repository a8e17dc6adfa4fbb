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
};

/// One E-step for the current source positions `moved` against `target` with variance sigma2 and outlier
/// weight w. With `truncation` > 0, kernel values below it are skipped by a KD-tree radius search (only
/// worth it once sigma is small against the set; `use_truncation` decides that). The dense path computes
/// kernel values in float unless `precise`.
Expectation expectation(const Points& moved, const Points& target, double sigma2, double outlier_weight,
                        int threads, double truncation = 0.0, bool precise = false);

/// The classic initial variance: mean squared distance over all source-target pairs, divided by 3.
double initial_sigma2(const Points& source, const Points& target);

/// Whether a truncated E-step pays off: the truncation radius is small against the source's extent.
bool use_truncation(const Points& moved, double sigma2, double truncation);

/// Validates a point set for CPD, naming it in the message ("source", "target").
void check_cpd_points(const Points& points, const char* name);

/// Validates w and the tolerance.
void check_cpd_common(double outlier_weight, double tolerance, int max_iterations);

}  // namespace partreg::core::detail

#include <functional>

#include "partreg/core/cpd.hpp"

namespace partreg::core::detail {

/// What every CPD variant's EM loop needs to know.
struct EmControl {
  double outlier_weight = 0.1;
  double tolerance = 1e-6;
  int max_iterations = 150;
  int threads = 0;
  double truncation = 0.0;  ///< 0 = always dense
  bool precise = false;     ///< double-precision dense E-step (the exact non-rigid path)
};

struct EmOutcome {
  double sigma2 = 0.0;
  int iterations = 0;
  CpdStopReason stop_reason = CpdStopReason::max_iterations;
};

/// The EM loop: E-step on `moved`, then `m_step` (which updates `moved` and returns the new sigma2),
/// until the negative log-likelihood settles, sigma2 collapses, or the cap is hit.
EmOutcome run_em(const Points& target, Points& moved, const EmControl& control,
                 const std::function<double(const Expectation&, double sigma2)>& m_step);

/// The seconds elapsed since `start` (a steady_clock time point in nanoseconds since its epoch).
double seconds_since(std::int64_t start_nanoseconds);
std::int64_t now_nanoseconds();

}  // namespace partreg::core::detail
