// Leave-one-out registration on real data: train without an instance, then register it under a 0.3 rad
// rotation and a translation of 3% of the diagonal. The result must beat rigid alignment of the mean shape.
#include <gtest/gtest.h>

#include "partreg/core/registration.hpp"
#include "partreg/core/training.hpp"
#include "partreg/core/truth_errors.hpp"
#include "partreg/io/dataset.hpp"
#include "support/shared_data.hpp"
#include "support/test_shapes.hpp"

namespace partreg {
namespace {

struct LeaveOneOut {
  core::CategoryModel model;
  core::Points observed;  ///< the held-out instance, moved
};

LeaveOneOut leave_out(const std::string& folder, std::size_t held_out) {
  io::Dataset dataset = io::read_dataset(testing::shared_data(folder));
  const core::TrainingInstance instance = dataset.instances[held_out];
  dataset.instances.erase(dataset.instances.begin() + static_cast<long>(held_out));
  LeaveOneOut setup;
  setup.model = core::train_category(dataset.name, dataset.instances, dataset.part_names, {});
  const double diagonal = core::bounding_box_diagonal(instance.points);
  const Eigen::Matrix3d R = testing::rotation(0.3, {1.0, 1.0, 1.0});
  const Eigen::Vector3d t = Eigen::Vector3d(1.0, -1.0, 1.0).normalized() * 0.03 * diagonal;
  setup.observed = (instance.points * R.transpose()).rowwise() + t.transpose();
  return setup;
}

// Eq. 5 of each variant against that of the mean shape aligned rigidly (latent pinned to 0 by the prior).
void expect_better_than_rigid_mean(const LeaveOneOut& setup, const std::vector<core::Variant>& variants) {
  const double scale2 = setup.model.normalization.scale * setup.model.normalization.scale;
  core::RegistrationSettings rigid;
  rigid.objective.prior_weight = 1e6;
  rigid.refinement.enabled = false;  // rigid: no fit beyond the (pinned) shape space either
  const double rigid_error =
      core::closest_point_error(core::register_observation(setup.model, setup.observed, rigid).deformed,
                                setup.observed) /
      scale2;
  for (core::Variant variant : variants) {
    core::RegistrationSettings settings;
    settings.variant = variant;
    const auto result = core::register_observation(setup.model, setup.observed, settings);
    const double error = core::closest_point_error(result.deformed, setup.observed) / scale2;
    std::cerr << setup.model.category << " " << core::enum_name(variant) << ": Eq. 5 " << error
              << " (rigid mean shape " << rigid_error << ")\n";
    EXPECT_LT(error, 0.9 * rigid_error) << core::enum_name(variant);  // at least 10% better
  }
}

TEST(RealDataRegistration, HeldOutKettleBeatsTheRigidMeanShape) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("kettles"));
  expect_better_than_rigid_mean(leave_out("kettles", 4),
                                {core::Variant::holistic, core::Variant::partwise, core::Variant::hol_part});
}

TEST(RealDataRegistration, HeldOutDrillBeatsTheRigidMeanShape) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("drills"));
  expect_better_than_rigid_mean(leave_out("drills", 2), {core::Variant::holistic});
}

// The pose search exists for this: real unseen mugs turned half round their up axis (the handle on the other
// side) register as well as unturned; a single start does not. Means over three held-out mugs, so that one
// ambiguous mug (the search keeps the truth-best hypothesis 78% of the time: docs/registration.md) does not
// decide.
TEST(RealDataRegistration, MugsTurnedHalfRoundRegisterAsWellAsUnturned) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("mugs"));
  const io::Dataset dataset = io::read_dataset(testing::shared_data("mugs"));
  double unturned = 0.0, turned = 0.0, single_turned = 0.0;
  for (std::size_t held : {1, 3, 5}) {
    std::vector<core::TrainingInstance> training = dataset.instances;
    const core::TrainingInstance instance = training[held];
    training.erase(training.begin() + static_cast<long>(held));
    const core::CategoryModel model = core::train_category(dataset.name, training, {}, {});
    const double diagonal = core::truth_diagonal(instance.points);
    auto error_at = [&](double yaw, const core::RegistrationSettings& settings) {
      const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
      const core::Points seen = instance.points * R.transpose();
      return core::measure_against_truth(core::register_observation(model, seen, settings).deformed, {}, {},
                                         seen, diagonal)
          .symmetric_rms_per_diagonal;
    };
    const core::RegistrationSettings search;  // the defaults search the yaw all round
    core::RegistrationSettings single;
    single.initialisation.restarts = 1;
    unturned += error_at(0.0, search) / 3;
    turned += error_at(M_PI, search) / 3;
    single_turned += error_at(M_PI, single) / 3;
  }
  std::cerr << "mugs: mean symmetric RMS " << unturned << " unturned, " << turned
            << " turned 180 degrees; single start turned " << single_turned << "\n";
  EXPECT_LT(turned, 1.15 * unturned);
  EXPECT_GT(single_turned, 1.15 * unturned);  // without the search the turned mugs are registered wrongly
}

// Drills stand on z (../shared/data/README.md). Trained with that up axis, the model's search turns about z
// unasked, and a drill turned a quarter round z registers as well as unturned; searched about y (the
// default axis of a model trained without --up) it does not.
TEST(RealDataRegistration, ADrillModelSearchesAboutItsOwnUpAxis) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("drills"));
  const io::Dataset dataset = io::read_dataset(testing::shared_data("drills"));
  std::vector<core::TrainingInstance> training = dataset.instances;
  const core::TrainingInstance instance = training[2];
  training.erase(training.begin() + 2);
  core::TrainingSettings z_up;
  z_up.up = Eigen::Vector3d(0, 0, 3);  // any length
  const core::CategoryModel model = core::train_category(dataset.name, training, {}, z_up);
  EXPECT_EQ(model.up, Eigen::Vector3d::UnitZ());
  const double diagonal = core::truth_diagonal(instance.points);
  auto error_at = [&](double yaw, const core::RegistrationSettings& settings) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const core::Points seen = instance.points * R.transpose();
    return core::measure_against_truth(core::register_observation(model, seen, settings).deformed, {}, {},
                                       seen, diagonal)
        .symmetric_rms_per_diagonal;
  };
  const core::RegistrationSettings model_up;  // unset: the model's z
  core::RegistrationSettings y_up;
  y_up.initialisation.up = Eigen::Vector3d::UnitY();
  const double unturned = error_at(0.0, model_up), turned = error_at(M_PI / 2, model_up),
               turned_about_y = error_at(M_PI / 2, y_up);
  std::cerr << "drill: symmetric RMS " << unturned << " unturned, " << turned
            << " turned 90 degrees about z; " << turned_about_y << " when the search turns about y\n";
  EXPECT_LT(turned, 1.15 * unturned);
  EXPECT_GT(turned_about_y, 1.15 * unturned);
}

}  // namespace
}  // namespace partreg
