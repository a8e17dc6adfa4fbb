#include "cpd_dense_kernel.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace partreg::core::detail {

// Far below any posterior that matters, far above float's smallest normal value (1e-38).
constexpr double kNegligibleKernel = 1e-30;

double dense_posterior_sums(const float* sx, const float* sy, const float* sz, const float* sw, std::ptrdiff_t m,
                            const double* target, const double* tw, std::ptrdiff_t count, float scale, double c,
                            float* work, float* p1, float* px, float* py, float* pz, double* mass) {
  using Array = Eigen::Map<Eigen::ArrayXf>;
  using ConstArray = Eigen::Map<const Eigen::ArrayXf>;
  const ConstArray mx(sx, m), my(sy, m), mz(sz, m), weight(sw, m);
  Array k(work, m), a1(p1, m), ax(px, m), ay(py, m), az(pz, m);
  double log_sum = 0.0;
  // Floored: with w = 0 a target point far from every source point would otherwise divide by zero.
  const double floor = std::max(c, 1e-300);
  for (std::ptrdiff_t n = 0; n < count; ++n) {
    const auto x = static_cast<float>(target[3 * n]), y = static_cast<float>(target[3 * n + 1]),
               z = static_cast<float>(target[3 * n + 2]);
    k = (((mx - x).square() + (my - y).square() + (mz - z).square()) * scale).exp();
    const double kernel_sum = static_cast<double>((k * weight).sum()), denominator = kernel_sum + floor;
    mass[n] = 1.0 - floor / denominator;
    log_sum += tw[n] * std::log(denominator);
    // A point whose kernel values all (nearly) underflowed is an outlier whatever w: its share of the sums is
    // negligible unless w = 0, where tw / denominator overflows float (inf x 0: NaN in every sum).
    if (!(kernel_sum > kNegligibleKernel)) continue;
    k *= static_cast<float>(tw[n] / denominator);
    a1 += k;
    ax += k * x;
    ay += k * y;
    az += k * z;
  }
  return log_sum;
}

}  // namespace partreg::core::detail
