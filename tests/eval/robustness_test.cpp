// A held-out kettle under the paper's largest outlier level (20% uniform in the box twice the object's
// size): registration samples its farthest points among the points with company and matches a point that
// stands alone only while the fit passes near it. Without that, farthest-point sampling favoured the outliers
// and the fit was worse than a rigid template (docs/registration.md, "Strays").
#include <gtest/gtest.h>

#include <iostream>

#include "partreg/core/registration.hpp"
#include "partreg/core/training.hpp"
#include "partreg/core/truth_errors.hpp"
#include "partreg/eval/perturbation.hpp"
#include "partreg/io/dataset.hpp"
#include "support/shared_data.hpp"

namespace partreg {
namespace {

TEST(RealDataRobustness, TwentyPercentOutliersLeaveAHeldOutKettleNearItsCleanFit) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("kettles"));
  io::Dataset dataset = io::read_dataset(testing::shared_data("kettles"));
  const core::Points truth = dataset.instances[0].points;
  dataset.instances.erase(dataset.instances.begin());
  const core::CategoryModel model = core::train_category(dataset.name, dataset.instances, dataset.part_names, {});
  const double diagonal = core::truth_diagonal(truth);
  const core::Points outliers =
      eval::perturb(truth, eval::Perturbation::outliers, 0.2, diagonal, /*seed=*/7).points;
  const auto error = [&](const core::Points& observed, double stray_limit) {
    core::RegistrationSettings settings;
    settings.sampling.stray_limit = stray_limit;
    const core::RegistrationResult result = core::register_observation(model, observed, settings);
    return core::measure_against_truth(result.deformed, result.part, model.part_names, truth, diagonal)
        .symmetric_rms_per_diagonal;
  };
  const double clean = error(truth, core::SamplingSettings{}.stray_limit);
  const double with_strays_out = error(outliers, core::SamplingSettings{}.stray_limit);
  const double with_every_point = error(outliers, 0.0);
  std::cerr << "symmetric RMS / diagonal: clean " << clean << ", 20% outliers " << with_strays_out
            << ", every point kept " << with_every_point << "\n";
  // Measured 0.0211 against 0.0338 (0.0107 clean): the strays out take away 60% of what the outliers added.
  // Issue 15's target (1.2x clean) is not met: the outliers the fit passes near are still matched.
  EXPECT_LT(with_strays_out, 0.75 * with_every_point);
  EXPECT_LT(with_strays_out, 2.2 * clean);
}

}  // namespace
}  // namespace partreg
