// Leave-one-out registration on real data: train without an instance, then register it under a 0.3 rad
// rotation and a translation of 3% of the diagonal. The result must beat rigid alignment of the mean shape.
#include <gtest/gtest.h>

#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/training/training.hpp"
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
// side), or tilted as the paper's largest rotation (0.65 rad about each of x, y and z: the up axis tilts by
// 0.9 rad), register as well as unturned; a single start does not, nor a search over yaws alone. Means over
// three held-out mugs, so that one ambiguous mug (the search keeps a hypothesis within 10% of the truth-best
// 89% of the time: docs/registration.md) does not decide.
TEST(RealDataRegistration, MugsTurnedOrTiltedRegisterAsWellAsUnturned) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("mugs"));
  const io::Dataset dataset = io::read_dataset(testing::shared_data("mugs"));
  const Eigen::Matrix3d half_round = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d tilted =
      (Eigen::AngleAxisd(0.65, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(-0.65, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(0.65, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  double unturned = 0.0, turned = 0.0, single_turned = 0.0, tilt = 0.0, yaws_only_tilt = 0.0;
  for (std::size_t held : {1, 3, 5}) {
    std::vector<core::TrainingInstance> training = dataset.instances;
    const core::TrainingInstance instance = training[held];
    training.erase(training.begin() + static_cast<long>(held));
    const core::CategoryModel model = core::train_category(dataset.name, training, {}, {});
    const double diagonal = core::truth_diagonal(instance.points);
    auto error_at = [&](const Eigen::Matrix3d& R, const core::RegistrationSettings& settings) {
      const core::Points seen = instance.points * R.transpose();
      return core::measure_against_truth(core::register_observation(model, seen, settings).deformed, {}, {},
                                         seen, diagonal)
                 .symmetric_rms_per_diagonal /
             3;
    };
    const core::RegistrationSettings
        search;  // the defaults search the yaw all round, and tilts of up to 1 rad
    core::RegistrationSettings single, yaws_only;
    single.initialisation.restarts = 1;
    single.initialisation.max_tilt = yaws_only.initialisation.max_tilt = 0.0;
    unturned += error_at(Eigen::Matrix3d::Identity(), search);
    turned += error_at(half_round, search);
    single_turned += error_at(half_round, single);
    tilt += error_at(tilted, search);
    yaws_only_tilt += error_at(tilted, yaws_only);
  }
  std::cerr << "mugs: mean symmetric RMS " << unturned << " unturned, " << turned
            << " turned 180 degrees (single start: " << single_turned << "), " << tilt
            << " tilted 0.65 rad about x, y and z (yaws alone: " << yaws_only_tilt << ")\n";
  EXPECT_LT(turned, 1.15 * unturned);
  EXPECT_GT(single_turned, 1.15 * unturned);  // without the search the turned mugs are registered wrongly
  EXPECT_LT(tilt, 1.2 * unturned);
  EXPECT_GT(yaws_only_tilt, 1.2 * unturned);  // without tilts the tilted mugs are registered wrongly
}

// Drills stand on z (../shared/data/README.md). Trained with that up axis, the model's search turns about z
// unasked, and a drill turned half round z registers as well as unturned; searched about y (the default axis
// of a model trained without --up) without tilts it does not: the turn flips y, which no yaw about y undoes.
// (A quarter turn about z is no longer a test of this: the symmetric direction converges from it about y.)
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
  // The space fit alone: the refinement after it would fit the surface from a wrong pose as well, which
  // the surface figure would not show.
  core::RegistrationSettings model_up;  // up unset: the model's z
  model_up.refinement.enabled = false;
  core::RegistrationSettings y_up = model_up;
  y_up.initialisation.up = Eigen::Vector3d::UnitY();
  y_up.initialisation.max_tilt = 0.0;
  const double unturned = error_at(0.0, model_up), turned = error_at(M_PI, model_up),
               turned_about_y = error_at(M_PI, y_up);
  std::cerr << "drill: symmetric RMS " << unturned << " unturned, " << turned
            << " turned 180 degrees about z; " << turned_about_y
            << " when the search turns about y, untilted\n";
  EXPECT_LT(turned, 1.15 * unturned);
  EXPECT_GT(turned_about_y, 1.15 * unturned);
}

}  // namespace
}  // namespace partreg
