// The coupled part variant: one problem over the object's pose, the parts' latents and small
// rigid offsets, with a seam term. Synthetic mugs with ground truth, fixed seeds.

#include <gtest/gtest.h>

#include <map>
#include <optional>

#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/core/training/training.hpp"
#include "support/test_shapes.hpp"

namespace partreg::core {
namespace {

struct Setup {
  CategoryModel model;
  Points held_out;  // the held-out mug's dense samples (data units, its own frame)
};

// Nine synthetic mugs train the model (default floor of points per part); the tenth is held out.
Setup make_setup() {
  const std::vector<SyntheticInstance> mugs = make_synthetic_category(SyntheticCategory::mug, 10, 21);
  std::vector<TrainingInstance> training;
  for (std::size_t i = 0; i + 1 < mugs.size(); ++i) {
    const auto samples = sample_correspondences(SyntheticCategory::mug, mugs[i].shape_parameters, 1500, 5);
    training.push_back({mugs[i].name, samples.points, samples.part, {}, {}});
  }
  TrainingSettings settings;
  settings.canonical_points = 600;
  Setup setup;
  setup.model = train_category("mugs", training, {"body", "handle"}, settings);
  setup.held_out =
      sample_correspondences(SyntheticCategory::mug, mugs.back().shape_parameters, 1500, 5).points;
  return setup;
}

const Setup& setup() {
  static const Setup instance = make_setup();
  return instance;
}

// The held-out mug turned by 0.3 rad about a tilted axis and moved by 3% of its diagonal.
Points observed_mug() {
  const Eigen::Matrix3d R = testing::rotation(0.3, {1.0, 1.0, 1.0});
  return (setup().held_out * R.transpose()).rowwise() + Eigen::RowVector3d(0.004, -0.003, 0.002);
}

struct Outcome {
  SeamGap gap;
  double symmetric_rms = 0.0;  // per diagonal of the truth
  RegistrationResult result;
};

Outcome register_as(Variant variant, const Points& observed, std::optional<double> seam_weight = {}) {
  RegistrationSettings settings;
  settings.variant = variant;
  settings.objective.seam_weight = seam_weight;
  Outcome outcome;
  outcome.result = register_observation(setup().model, observed, settings);
  outcome.gap = seam_gap(setup().model, outcome.result);
  outcome.symmetric_rms =
      measure_against_truth(outcome.result.deformed, outcome.result.part, setup().model.part_names, observed,
                            truth_diagonal(setup().held_out))
          .symmetric_rms_per_diagonal;
  std::cerr << enum_name(variant) << ": seam gap max " << outcome.gap.max << ", mean " << outcome.gap.mean
            << " over " << outcome.gap.points << " boundary points; symmetric RMS " << outcome.symmetric_rms
            << " of the diagonal\n";
  return outcome;
}

TEST(CoupledRegistration, TheHandleStaysAttachedWherePartwiseComesApart) {
  const Points observed = observed_mug();
  std::map<Variant, Outcome> outcomes;
  for (Variant variant : {Variant::holistic, Variant::partwise, Variant::hol_part, Variant::coupled})
    outcomes[variant] = register_as(variant, observed);
  // The seam weight training chose for these mugs: the soft seam (1) fits held-out synthetic mugs best.
  ASSERT_EQ(setup().model.training.seam_weight, 1.0) << setup().model.training.seam_weight_choice;
  const Outcome stiff = register_as(Variant::coupled, observed, 10.0);
  const Outcome& coupled = outcomes[Variant::coupled];
  const Outcome& partwise = outcomes[Variant::partwise];
  ASSERT_GT(coupled.gap.points, 10);
  // With a stiff seam, the target, under 0.5% of the diagonal, on the mean over the boundary points
  // (measured 0.32%; the largest gap is 0.78%). Partwise's parts come apart by twenty times that (measured
  // 7.3%, 11.9% at most).
  EXPECT_LT(stiff.gap.mean, 0.005);
  EXPECT_LT(stiff.gap.max, 0.015);
  EXPECT_GT(partwise.gap.mean, 0.005);
  EXPECT_GT(partwise.gap.max, 0.01);
  // With the category's own soft seam the handle gives a little (measured 0.69%, 1.66% at most: over the
  // target on this mug, 0.47% on average over the synthetic mugs' evaluation, docs/results.md) and stays an
  // order of magnitude closer than partwise's or hol+part's (5.0%).
  EXPECT_LT(coupled.gap.mean, 0.15 * partwise.gap.mean);
  EXPECT_LT(coupled.gap.mean, 0.15 * outcomes[Variant::hol_part].gap.mean);
  // Attached without giving up the fit (symmetric RMS measured 0.85% against holistic 1.49%, partwise 1.20%,
  // hol+part 1.15%; 0.81% with the stiff seam): a coupling that merely froze the parts at the holistic fit
  // would fail the first.
  for (const Outcome* fit : {&coupled, &stiff}) {
    EXPECT_LT(fit->symmetric_rms, 0.8 * outcomes[Variant::holistic].symmetric_rms);
    EXPECT_LT(fit->symmetric_rms, 0.9 * partwise.symmetric_rms);
    EXPECT_LT(fit->symmetric_rms, 1.1 * outcomes[Variant::hol_part].symmetric_rms);
  }
}

}  // namespace
}  // namespace partreg::core
