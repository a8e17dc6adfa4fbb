#pragma once
// The hot loop of the fast CPD E-step, on plain arrays (internal to partreg_core). It lives in its own
// translation unit so that it alone can be compiled with AVX2/FMA: it allocates nothing through Eigen, so
// no Eigen object crosses between code built with different alignment settings.

#include <cstddef>

namespace partreg::core::detail {

/// Posterior sums of `count` weighted target points against m weighted source points, in float (EM's
/// weights need no more). Sources: separate coordinate arrays sx, sy, sz and weights sw (how many points
/// each stands for). Targets: row-major x y z doubles and weights tw. Accumulates p1 += P 1 and
/// p{x,y,z} += P X per source (per point it stands for), writes mass[n] = (P^T 1)_n per target point, and
/// returns the sum of tw log(denominator). `scale` is -1 / (2 sigma2); `c` the outlier term. `work` holds m
/// floats. Coordinates should be small (relative to a nearby origin) for float to resolve sigma.
double dense_posterior_sums(const float* sx, const float* sy, const float* sz, const float* sw, std::ptrdiff_t m,
                            const double* target, const double* tw, std::ptrdiff_t count, float scale, double c,
                            float* work, float* p1, float* px, float* py, float* pz, double* mass);

}  // namespace partreg::core::detail
