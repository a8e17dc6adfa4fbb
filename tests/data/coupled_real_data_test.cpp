// The coupled part variant on real kettles (four parts, one file per part): leave one kettle out, register
// it under a 0.3 rad rotation and a shift of 3% of its diagonal, and compare the parts' seams, the
// symmetric RMS error and each part against its own part of the kettle with the other variants.
#include <gtest/gtest.h>

#include <map>

#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/io/dataset.hpp"
#include "support/shared_data.hpp"
#include "support/test_shapes.hpp"

namespace partreg {
namespace {

struct Figures {
  core::SeamGap gap;
  double symmetric_rms = 0.0;  // per diagonal of the true kettle
  core::TruthErrors errors;
};

TEST(CoupledRealData, HeldOutKettleKeepsItsPartsTogether) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("kettles"));
  io::Dataset dataset = io::read_dataset(testing::shared_data("kettles"));
  const core::TrainingInstance instance = dataset.instances[4];
  dataset.instances.erase(dataset.instances.begin() + 4);
  const core::CategoryModel model =
      core::train_category(dataset.name, dataset.instances, dataset.part_names, {});
  ASSERT_EQ(model.spaces.size(), 5u);  // holistic + body, handle, lid, spout
  const double diagonal = core::truth_diagonal(instance.points);
  const Eigen::Matrix3d R = testing::rotation(0.3, {1.0, 1.0, 1.0});
  const Eigen::Vector3d t = Eigen::Vector3d(1.0, -1.0, 1.0).normalized() * 0.03 * diagonal;
  const core::Points observed = (instance.points * R.transpose()).rowwise() + t.transpose();
  std::map<core::Variant, Figures> figures;
  for (core::Variant variant :
       {core::Variant::holistic, core::Variant::partwise, core::Variant::hol_part, core::Variant::coupled}) {
    core::RegistrationSettings settings;
    settings.variant = variant;
    const core::RegistrationResult result = core::register_observation(model, observed, settings);
    Figures& f = figures[variant];
    f.gap = core::seam_gap(model, result);
    // The observed rows are the kettle's own sample, moved: its part files label them.
    f.errors = core::measure_against_truth(result.deformed, result.part, model.part_names, observed, diagonal,
                                           nullptr, &instance.part);
    f.symmetric_rms = f.errors.symmetric_rms_per_diagonal;
    std::cerr << core::enum_name(variant) << ": symmetric RMS " << f.symmetric_rms << ", seam gap max "
              << f.gap.max << " mean " << f.gap.mean << " over " << f.gap.points << " points; each part "
              << "against its own: mean " << *f.errors.own_part_rms_mean_per_diagonal;
    for (const auto& [part, figure] : f.errors.own_part_rms_per_diagonal) std::cerr << ' ' << part << ' ' << figure;
    std::cerr << '\n';
  }
  const Figures& coupled = figures[core::Variant::coupled];
  ASSERT_GT(coupled.gap.points, 20);
  // The seam term closes most of the gap the independent parts leave ...
  EXPECT_LT(coupled.gap.mean, 0.5 * figures[core::Variant::partwise].gap.mean);
  EXPECT_LT(coupled.gap.mean, 0.5 * figures[core::Variant::hol_part].gap.mean);
  // ... without giving up the fit: level with the holistic fit it starts from (measured 0.00906 against
  // 0.00907 with the search over tilts and the symmetric direction; 5% allows that, a coupling that pulled
  // the parts off the surface would not pass).
  EXPECT_LT(coupled.symmetric_rms, 1.05 * figures[core::Variant::holistic].symmetric_rms);
  // Every part on its own part of the kettle: measured 0.008-0.011 of the diagonal each (mean 0.0098 against
  // holistic's 0.0096). A kettle turned half a turn puts the handle 0.45 from its own, a handle pressed onto
  // the body or a spout left off the kettle is several hundredths away; the whole-truth figure above sees
  // neither.
  for (const auto& [part, figure] : coupled.errors.own_part_rms_per_diagonal) EXPECT_LT(figure, 0.02) << part;
  EXPECT_EQ(coupled.errors.own_part_rms_per_diagonal.size(), 4u);
  EXPECT_LT(*coupled.errors.own_part_rms_mean_per_diagonal,
            1.1 * *figures[core::Variant::holistic].errors.own_part_rms_mean_per_diagonal);
}

}  // namespace
}  // namespace partreg
