#include "cpd_expectation.hpp"

#include <cmath>
#include <mutex>

#include "cpd_dense_kernel.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/kdtree.hpp"
#include "partreg/core/normalization.hpp"
#include "partreg/core/parallel.hpp"

namespace partreg::core::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFloor = 1e-300;

// Per-thread partial sums, merged under a lock once per thread.
struct Partial {
  Eigen::VectorXd P1;
  Points PX;
  double nll = 0.0;
  explicit Partial(Eigen::Index m) : P1(Eigen::VectorXd::Zero(m)), PX(Points::Zero(m, 3)) {}
};

void merge(Expectation& total, const Partial& part, std::mutex& lock) {
  std::lock_guard<std::mutex> guard(lock);
  total.P1 += part.P1;
  total.PX += part.PX;
  total.negative_log_likelihood += part.nll;
}

// Dense E-step over a range of target points, one target point at a time against all source points held as
// separate coordinate arrays, so that distances, exp and sums are vectorised. The fast path computes in float
// (twice the SIMD width; EM weights need no more) in a kernel of its own (cpd_dense_kernel.cpp); the exact
// path in double here.
void dense_range_fast(const Points& moved, const Points& target, Eigen::Index begin, Eigen::Index end,
                      double sigma2, double c, Partial& partial, Expectation& out) {
  const Eigen::Index m = moved.rows();
  std::vector<float> buffer(static_cast<std::size_t>(8 * m), 0.0f);  // x y z, work, p1 px py pz
  float* b = buffer.data();
  for (Eigen::Index i = 0; i < m; ++i)
    for (int d = 0; d < 3; ++d) b[d * m + i] = static_cast<float>(moved(i, d));
  partial.nll -= dense_posterior_sums(b, b + m, b + 2 * m, m, target.data(), begin, end,
                                      static_cast<float>(-0.5 / sigma2), c, b + 3 * m, b + 4 * m, b + 5 * m,
                                      b + 6 * m, b + 7 * m, out.Pt1.data());
  for (Eigen::Index i = 0; i < m; ++i) {
    partial.P1[i] += b[4 * m + i];
    for (int d = 0; d < 3; ++d) partial.PX(i, d) += b[(5 + d) * m + i];
  }
}

void dense_range_exact(const Points& moved, const Points& target, Eigen::Index begin, Eigen::Index end,
                       double sigma2, double c, Partial& partial, Expectation& out) {
  const Eigen::ArrayXd mx = moved.col(0), my = moved.col(1), mz = moved.col(2);
  Eigen::ArrayXd k(moved.rows());
  for (Eigen::Index n = begin; n < end; ++n) {
    const double x = target(n, 0), y = target(n, 1), z = target(n, 2);
    k = (((mx - x).square() + (my - y).square() + (mz - z).square()) * (-0.5 / sigma2)).exp();
    const double denominator = std::max(k.sum() + c, kFloor);
    k /= denominator;
    partial.P1 += k.matrix();
    partial.PX.col(0) += (k * x).matrix();
    partial.PX.col(1) += (k * y).matrix();
    partial.PX.col(2) += (k * z).matrix();
    out.Pt1[n] = k.sum();
    partial.nll -= std::log(denominator);
  }
}

// Truncated E-step: only source points within the radius where the kernel exceeds `truncation`.
void truncated_range(const KdTree& tree, const Points& target, Eigen::Index begin, Eigen::Index end,
                     double sigma2, double c, double radius, Partial& partial, Expectation& out) {
  std::vector<std::pair<int, double>> neighbours;
  std::vector<double> kernel;
  for (Eigen::Index n = begin; n < end; ++n) {
    tree.radius(target.row(n).transpose(), radius, neighbours);
    kernel.resize(neighbours.size());
    double denominator = std::max(c, kFloor);
    for (std::size_t j = 0; j < neighbours.size(); ++j) {
      kernel[j] = std::exp(-0.5 * neighbours[j].second / sigma2);
      denominator += kernel[j];
    }
    double mass = 0.0;
    for (std::size_t j = 0; j < neighbours.size(); ++j) {
      const double p = kernel[j] / denominator;
      partial.P1[neighbours[j].first] += p;
      partial.PX.row(neighbours[j].first) += p * target.row(n);
      mass += p;
    }
    out.Pt1[n] = mass;
    partial.nll -= std::log(denominator);
  }
}

double truncation_radius(double sigma2, double truncation) {
  return std::sqrt(2.0 * sigma2 * std::log(1.0 / truncation));
}

}  // namespace

Expectation expectation(const Points& moved, const Points& target, double sigma2, double outlier_weight,
                        int threads, double truncation, bool precise) {
  const Eigen::Index m = moved.rows(), n = target.rows();
  Expectation out;
  out.P1 = Eigen::VectorXd::Zero(m);
  out.PX = Points::Zero(m, 3);
  out.Pt1.resize(n);
  // Uniform outlier term of the mixture, expressed in the kernel's scale (Myronenko & Song, Eq. 7).
  const double c = std::pow(2.0 * kPi * sigma2, 1.5) * outlier_weight / (1.0 - outlier_weight) *
                   static_cast<double>(m) / static_cast<double>(n);
  std::mutex lock;
  if (truncation > 0.0) {
    const KdTree tree(moved);
    const double radius = truncation_radius(sigma2, truncation);
    parallel_for(
        n,
        [&](Eigen::Index begin, Eigen::Index end) {
          Partial partial(m);
          truncated_range(tree, target, begin, end, sigma2, c, radius, partial, out);
          merge(out, partial, lock);
        },
        threads);
  } else {
    parallel_for(
        n,
        [&](Eigen::Index begin, Eigen::Index end) {
          Partial partial(m);
          if (precise)
            dense_range_exact(moved, target, begin, end, sigma2, c, partial, out);
          else
            dense_range_fast(moved, target, begin, end, sigma2, c, partial, out);
          merge(out, partial, lock);
        },
        threads, 128);
  }
  out.Np = out.P1.sum();
  out.negative_log_likelihood += 1.5 * static_cast<double>(n) * std::log(sigma2);
  return out;
}

double initial_sigma2(const Points& source, const Points& target) {
  const double m = static_cast<double>(source.rows()), n = static_cast<double>(target.rows());
  const Eigen::RowVector3d source_sum = source.colwise().sum(), target_sum = target.colwise().sum();
  const double total = n * source.squaredNorm() + m * target.squaredNorm() - 2.0 * source_sum.dot(target_sum);
  return total / (3.0 * m * n);
}

bool use_truncation(const Points& moved, double sigma2, double truncation) {
  if (truncation <= 0.0) return false;
  return truncation_radius(sigma2, truncation) < 0.1 * bounding_box_diagonal(moved);
}

void check_cpd_points(const Points& points, const char* name) {
  if (points.rows() < 3)
    throw InputError(std::string("CPD needs at least 3 ") + name + " points, got " +
                     std::to_string(points.rows()));
  if (!points.allFinite())
    throw InputError(std::string("the ") + name + " points hold NaN or infinite values");
}

void check_cpd_common(double outlier_weight, double tolerance, int max_iterations) {
  if (!(outlier_weight >= 0.0 && outlier_weight < 1.0))
    throw UsageError("the CPD outlier weight w must be in [0, 1), got " + std::to_string(outlier_weight));
  if (!(tolerance > 0.0)) throw UsageError("the CPD tolerance must be positive");
  if (max_iterations < 1) throw UsageError("the CPD iteration cap must be at least 1");
}

}  // namespace partreg::core::detail

#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace partreg::core::detail {

EmOutcome run_em(const Points& target, Points& moved, const EmControl& control,
                 const std::function<double(const Expectation&, double sigma2)>& m_step) {
  EmOutcome outcome;
  double sigma2 = initial_sigma2(moved, target);
  if (!(sigma2 > 0.0)) {
    outcome.stop_reason = CpdStopReason::degenerate;
    return outcome;
  }
  double previous = std::numeric_limits<double>::infinity();
  for (int iteration = 1; iteration <= control.max_iterations; ++iteration) {
    const double truncation = use_truncation(moved, sigma2, control.truncation) ? control.truncation : 0.0;
    const Expectation e = expectation(moved, target, sigma2, control.outlier_weight, control.threads,
                                      truncation, control.precise);
    outcome.iterations = iteration;
    if (!(e.Np > 1e-12)) {  // every target point explained as an outlier: nothing left to fit
      outcome.stop_reason = CpdStopReason::degenerate;
      break;
    }
    sigma2 = m_step(e, sigma2);
    // Relative to |L| + N: the log-likelihood can pass through zero, where a plain relative change explodes.
    const double change = std::abs(e.negative_log_likelihood - previous) /
                          (std::abs(e.negative_log_likelihood) + static_cast<double>(target.rows()));
    previous = e.negative_log_likelihood;
    if (!(sigma2 > 1e-12)) {  // an exact fit: the variance has nothing left to explain
      sigma2 = 1e-12;
      outcome.stop_reason = CpdStopReason::converged;
      break;
    }
    if (change < control.tolerance) {
      outcome.stop_reason = CpdStopReason::converged;
      break;
    }
  }
  outcome.sigma2 = sigma2;
  return outcome;
}

std::int64_t now_nanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double seconds_since(std::int64_t start_nanoseconds) {
  return static_cast<double>(now_nanoseconds() - start_nanoseconds) * 1e-9;
}

}  // namespace partreg::core::detail
