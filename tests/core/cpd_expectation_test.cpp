// The E-step's outlier term (core/core/src/cpd/cpd_expectation.hpp): CPD's density per point (1 / N) against
// a density per volume (1 / V), on one source point and two targets whose posteriors have a closed form.
#include "cpd/cpd_expectation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace partreg::core::detail {
namespace {

constexpr double kSigma = 0.01;
constexpr double kWeight = 0.1;

// The posterior of each target point for one source point at the origin: k / (k + c), with k the kernel
// exp(-d^2 / 2 sigma^2) and c the outlier term (2 pi sigma^2)^1.5 w / (1 - w) M / spread.
double posterior(double distance, double spread) {
  const double kernel = std::exp(-distance * distance / (2.0 * kSigma * kSigma));
  const double c = std::pow(2.0 * M_PI * kSigma * kSigma, 1.5) * kWeight / (1.0 - kWeight) / spread;
  return kernel / (kernel + c);
}

struct Posteriors {
  double on_surface, five_sigma_off;
};

Posteriors posteriors(double volume, bool exact) {
  const Points source = Points::Zero(1, 3);
  Points target(2, 3);
  target << 0.0, 0.0, 0.0, 5.0 * kSigma, 0.0, 0.0;
  EStepSettings settings;
  settings.outlier_weight = kWeight;
  settings.outlier_volume = volume;
  settings.exact = exact;
  settings.cell_size = 0.0;
  const Expectation e = expectation(source, target, kSigma * kSigma, settings);
  return {e.Pt1[0], e.Pt1[1]};
}

// CPD's 1 / N spreads the outliers over two "units" whatever the scale: at sigma = 0.01 a point 5 sigma off is
// then still more likely surface than outlier (0.81).
TEST(EStep, CpdsDensityPerPointCountsAPointFiveSigmaOffAsSurface) {
  for (const bool exact : {true, false}) {
    const Posteriors p = posteriors(0.0, exact);
    EXPECT_NEAR(p.five_sigma_off, posterior(5.0 * kSigma, 2.0), 1e-6);  // the E-step's own arithmetic differs in the 7th digit
    EXPECT_GT(p.five_sigma_off, 0.5);
  }
}

// Over a box of 0.1 (V = 1e-3, an object part's size in normalised units) the same point is an outlier and
// the point on the surface keeps almost all its mass.
TEST(EStep, ADensityPerVolumeCountsAPointFiveSigmaOffAsOutlier) {
  for (const bool exact : {true, false}) {
    const Posteriors p = posteriors(1e-3, exact);
    EXPECT_NEAR(p.five_sigma_off, posterior(5.0 * kSigma, 1e-3), 1e-6);  // the E-step's own arithmetic differs in the 7th digit
    EXPECT_NEAR(p.on_surface, posterior(0.0, 1e-3), 1e-6);  // the E-step's own arithmetic differs in the 7th digit
    EXPECT_LT(p.five_sigma_off, 0.01);
    EXPECT_GT(p.on_surface, 0.99);
  }
}

// Without outliers in the model (w = 0) a target point whose kernel values underflow float (15 sigma off, gathered
// by a wide truncation) overflowed the fast path's scale tw / denominator: NaN in every sum, and a refinement
// with refine-outliers 0 returned NaN points. The fast path now leaves such a point out; the exact path, in
// double, still gives it to its one source.
TEST(EStep, APointWhoseKernelsUnderflowLeavesTheSumsFiniteWithoutAnOutlierTerm) {
  for (const bool exact : {true, false}) {
    Points target(2, 3);
    target << 0.0, 0.0, 0.0, 15.0 * kSigma, 0.0, 0.0;  // exp(-112.5) is 0 in float
    EStepSettings settings;
    settings.outlier_weight = 0.0;
    settings.exact = exact;
    settings.cell_size = 0.0;
    settings.truncation = 1e-60;  // a radius of 16.6 sigma: the fast path gathers the far point
    const Expectation e = expectation(Points::Zero(1, 3), target, kSigma * kSigma, settings);
    ASSERT_TRUE(e.P1.allFinite() && e.PX.allFinite() && e.Pt1.allFinite()) << "exact " << exact;
    EXPECT_NEAR(e.Pt1[0], 1.0, 1e-6);
    EXPECT_NEAR(e.Pt1[1], exact ? 1.0 : 0.0, 1e-6);
    EXPECT_NEAR(e.P1[0], e.Pt1.sum(), 1e-6);
  }
}

}  // namespace
}  // namespace partreg::core::detail
