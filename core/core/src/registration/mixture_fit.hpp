#pragma once
// The space fit's finish on a noisy observation: EM over a Gaussian mixture (internal to partreg_core).
//
// Closest points are a biased estimator once the noise is larger than the detail: each observed point pulls
// its nearest canonical point, whichever side of the surface it fell on, and each canonical point finds some
// noisy point near it wherever it stands (docs/registration.md, "Noise"). The mixture instead explains every
// observed point by all the canonical points near it, at a variance EM estimates with the fit: the
// maximum-likelihood fit of the shape space to a noisy cloud. Within a step the posterior is fixed, so the
// step's cost is a weighted least squares onto each canonical point's posterior mean, the same weighted pairs
// the closest-point steps hand to MomentCost.

#include <cmath>
#include <vector>

#include "cpd/cpd_expectation.hpp"
#include "moment_cost.hpp"
#include "space_solver.hpp"

namespace partreg::core::detail {

/// The mixture's centres are canonical points; the canonical sample gives small parts a floor of points, so
/// its density is not even, and with a variance of several percent of the diagonal a dense part would
/// explain more of the observation than its surface does. The centres are therefore the farthest-point
/// subset of this share of the canonical points (an even spacing).
constexpr double kMixtureCentreShare = 0.6;

/// Which canonical rows centre the mixture (kMixtureCentreShare of them, evenly spread).
std::vector<bool> mixture_centres(const Points& canonical);

/// One registration's mixture: the observed points it explains and the variance, carried from step to step.
class Mixture {
 public:
  /// `targets`: the observed points to explain (the observation without the closest-point fit's strays);
  /// `centres`: the rows that may centre it (mixture_centres, over the rows the posed points will have).
  Mixture(Points targets, std::vector<bool> centres);

  /// The E-step for `posed` points (every row of the object or of one space) with the `visible` centres: each
  /// with posterior mass becomes a pair onto its posterior mean, weighted by its share of the mass. The first
  /// call starts the variance at the closest-point residual.
  std::vector<WeightedPair> pairs(const Points& posed, const std::vector<bool>& visible);

  /// The variance after the M-step moved the same rows to `posed`; true once it has settled (relative change
  /// below `tolerance`).
  bool update(const Points& posed, double tolerance);

  /// The standard deviation per axis after the last update (0 before the first E-step).
  double sigma() const { return std::sqrt(sigma2_); }

 private:
  Points targets_;
  std::vector<bool> centres_;
  std::vector<int> rows_;  ///< the last E-step's active rows
  Expectation expectation_;
  double sigma2_ = 0.0;
};

/// The prior's weight in a fit to an observation whose noise is `sigma` per axis (normalised length): the
/// settings' weight, times (sigma / mixture_noise)^2 above the noise where the mixture starts. A step's data
/// term is a mean squared distance, the negative log-likelihood times 2 sigma^2 / N, so the prior keeps its
/// share of the posterior only if its weight grows as the noise's variance; a prior light enough for clean
/// views otherwise lets a noisy fit bend the shape to the noise (docs/registration.md, "The prior").
double noisy_prior_weight(double sigma, const ObjectiveSettings& objective);

/// Continues a single space's fit in the mixture of `targets` from `solution` (its closest-point fit), for
/// at most the settings' outer iterations; `centres` as mixture_centres, over the space's own rows. Returns
/// the mixture's final standard deviation per axis (normalised length).
double finish_in_mixture(const ShapeSpace& space, const ViewSurface& surface, const Observation& observation,
                       const Points& targets, const std::vector<bool>& centres,
                       const RegistrationSettings& settings, SpaceSolution& solution);

}  // namespace partreg::core::detail
