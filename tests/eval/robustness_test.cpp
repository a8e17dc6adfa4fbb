// A held-out kettle under the paper's largest outlier level (20% uniform in the box twice the object's
// size): registration samples its farthest points among the points with company and matches a point that
// stands alone only while the fit passes near it (in the pose search's screening too), and the refinement spreads the outliers that remain over a
// volume, as many as the stray screen found. Without that, farthest-point sampling favoured the outliers
// and the fit was worse than a rigid template (docs/registration.md, "Strays"). And under the paper's second
// noise level: the refinement widens its kernel with the noise rather than stand down and leave the
// space fit (docs/refinement.md).
#include <gtest/gtest.h>

#include <iostream>

#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/eval/perturbation.hpp"
#include "partreg/io/dataset.hpp"
#include "support/shared_data.hpp"

namespace partreg {
namespace {

// The first kettle, and a model trained on the others.
struct HeldOutKettle {
  core::Points truth;
  core::CategoryModel model;
  double diagonal = 0.0;
};

const HeldOutKettle& held_out_kettle() {
  static const HeldOutKettle kettle = [] {
    io::Dataset dataset = io::read_dataset(testing::shared_data("kettles"));
    HeldOutKettle k;
    k.truth = dataset.instances[0].points;
    dataset.instances.erase(dataset.instances.begin());
    k.model = core::train_category(dataset.name, dataset.instances, dataset.part_names, {});
    k.diagonal = core::truth_diagonal(k.truth);
    return k;
  }();
  return kettle;
}

double error_of(const core::RegistrationResult& result) {
  const HeldOutKettle& k = held_out_kettle();
  return core::measure_against_truth(result.deformed, result.part, k.model.part_names, k.truth, k.diagonal)
      .symmetric_rms_per_diagonal;
}

TEST(RealDataRobustness, TwentyPercentOutliersLeaveAHeldOutKettleNearItsCleanFit) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("kettles"));
  const auto& [truth, model, diagonal] = held_out_kettle();
  const core::Points outliers =
      eval::perturb(truth, eval::Perturbation::outliers, 0.2, diagonal, /*seed=*/7).points;
  const auto registered = [&model = model](const core::Points& observed, double stray_limit) {
    core::RegistrationSettings settings;
    settings.sampling.stray_limit = stray_limit;
    return core::register_observation(model, observed, settings);
  };
  const core::RegistrationResult clean = registered(truth, core::SamplingSettings{}.stray_limit);
  const core::RegistrationResult strays_out = registered(outliers, core::SamplingSettings{}.stray_limit);
  const double clean_error = error_of(clean), with_strays_out = error_of(strays_out),
               with_every_point = error_of(registered(outliers, 0.0));
  std::cerr << "symmetric RMS / diagonal: clean " << clean_error << ", 20% outliers " << with_strays_out
            << ", every point kept " << with_every_point << "; refinement's outlier weight: clean "
            << clean.refinement.outlier_weight << ", 20% outliers " << strays_out.refinement.outlier_weight << "\n";
  // Measured 0.0154 against 0.0256 (0.0107 clean); 0.0169 while the pose search's screening dropped the
  // flags, 0.0197 while the refinement's outlier term was also CPD's 1 / N at a fixed w. The aim
  // of 1.2x clean is not met: the outliers the fit passes near are matched.
  EXPECT_LT(with_strays_out, 0.75 * with_every_point);
  EXPECT_LT(with_strays_out, 1.6 * clean_error);
  // The refinement's w is the share the stray screen left out, a lower bound of the outliers' (measured 0.0113:
  // most of them pass within 0.1 of the surface), and the floor on the clean instance, which has no strays.
  EXPECT_GT(strays_out.refinement.outlier_weight, 0.005);
  EXPECT_LT(strays_out.refinement.outlier_weight, 0.2);
  EXPECT_EQ(clean.refinement.outlier_weight, core::RefinementSettings{}.outlier_weight);
}

TEST(RealDataRobustness, TheRefinementStillHelpsAHeldOutKettleUnderNoise) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("kettles"));
  const auto& [truth, model, diagonal] = held_out_kettle();
  // The paper's noise of 0.01 m for a 0.3 m object: sigma 3.3% of the diagonal on every coordinate.
  const core::Points noisy = eval::perturb(truth, eval::Perturbation::noise,
                                           eval::relative_level(eval::Perturbation::noise, 0.01),
                                           diagonal, /*seed=*/7).points;
  core::RegistrationSettings refined, space_fit, fixed_kernel;
  space_fit.refinement.enabled = false;
  fixed_kernel.refinement.noise_width = 0.0;
  const core::RegistrationResult result = core::register_observation(model, noisy, refined);
  const double clean = error_of(core::register_observation(model, truth, refined));
  const double widened = error_of(result);
  const double space = error_of(core::register_observation(model, noisy, space_fit));
  const double fixed = error_of(core::register_observation(model, noisy, fixed_kernel));
  std::cerr << "symmetric RMS / diagonal: clean " << clean << "; noise 0.033: refined " << widened
            << " (noise read " << result.refinement.noise << ", kernel " << result.refinement.width
            << "), space fit alone " << space << ", refined at refine-beta " << fixed << "\n";
  // Measured: noise read 0.036, kernel 0.144; refined 0.0177, space fit alone 0.0277 (what the stand-down
  // left), refined at 0.05 0.0223 (the field follows the noise); clean 0.0107.
  EXPECT_GT(result.refinement.noise, 0.7 * 0.0333);
  EXPECT_LT(result.refinement.noise, 1.4 * 0.0333);
  EXPECT_LT(widened, 0.85 * space);
  EXPECT_LT(widened, 0.85 * fixed);
}

}  // namespace
}  // namespace partreg
