#include "cpd_dense_kernel.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace partreg::core::detail {

double dense_posterior_sums(const float* sx, const float* sy, const float* sz, std::ptrdiff_t m,
                            const double* target, std::ptrdiff_t begin, std::ptrdiff_t end, float scale,
                            double c, float* work, float* p1, float* px, float* py, float* pz, double* pt1) {
  using Array = Eigen::Map<Eigen::ArrayXf>;
  using ConstArray = Eigen::Map<const Eigen::ArrayXf>;
  const ConstArray mx(sx, m), my(sy, m), mz(sz, m);
  Array k(work, m), a1(p1, m), ax(px, m), ay(py, m), az(pz, m);
  double log_sum = 0.0;
  for (std::ptrdiff_t n = begin; n < end; ++n) {
    const auto x = static_cast<float>(target[3 * n]), y = static_cast<float>(target[3 * n + 1]),
               z = static_cast<float>(target[3 * n + 2]);
    k = (((mx - x).square() + (my - y).square() + (mz - z).square()) * scale).exp();
    // Floored: with w = 0 a target point far from every source point would otherwise divide by zero.
    const double denominator = std::max(static_cast<double>(k.sum()) + c, 1e-300);
    k *= static_cast<float>(1.0 / denominator);
    a1 += k;
    ax += k * x;
    ay += k * y;
    az += k * z;
    pt1[n] = static_cast<double>(k.sum());
    log_sum += std::log(denominator);
  }
  return log_sum;
}

}  // namespace partreg::core::detail
