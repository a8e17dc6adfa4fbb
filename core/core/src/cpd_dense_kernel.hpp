#pragma once
// The hot loop of the dense CPD E-step, on plain arrays (internal to partreg_core). It lives in its own
// translation unit so that it alone can be compiled with AVX2/FMA: it allocates nothing through Eigen, so
// no Eigen object crosses between code built with different alignment settings.

#include <cstddef>

namespace partreg::core::detail {

/// Accumulates, for target points [begin, end) (row-major x y z doubles), the posterior sums against the
/// m source points given as separate float coordinate arrays: p1 += P 1, p{x,y,z} += P X, pt1[n] = (P^T 1)_n,
/// and returns the sum of log denominators. `scale` is -1 / (2 sigma2); `c` the outlier term. `work` holds m
/// floats.
double dense_posterior_sums(const float* sx, const float* sy, const float* sz, std::ptrdiff_t m,
                            const double* target, std::ptrdiff_t begin, std::ptrdiff_t end, float scale,
                            double c, float* work, float* p1, float* px, float* py, float* pz, double* pt1);

}  // namespace partreg::core::detail
