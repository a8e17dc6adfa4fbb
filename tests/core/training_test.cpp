#include "partreg/core/training/training.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/synthetic/synthetic.hpp"

namespace partreg::core {
namespace {

TrainingInstance instance_of(const SyntheticInstance& synthetic, int samples) {
  TrainingInstance instance;
  instance.name = synthetic.name;
  const auto gt = sample_correspondences(SyntheticCategory::mug, synthetic.shape_parameters, samples, 7);
  instance.points = gt.points;
  instance.part = gt.part;
  return instance;
}

TEST(Synthetic, IsDeterministicAndVariesWithTheSeed) {
  const auto a = make_synthetic_instance(SyntheticCategory::drill, 4, 2);
  const auto b = make_synthetic_instance(SyntheticCategory::drill, 4, 2);
  const auto c = make_synthetic_instance(SyntheticCategory::drill, 5, 2);
  EXPECT_EQ(a.shape_parameters, b.shape_parameters);
  EXPECT_NE(a.shape_parameters, c.shape_parameters);
  EXPECT_EQ(a.parts[2].mesh.vertices, b.parts[2].mesh.vertices);
  EXPECT_EQ(part_names(SyntheticCategory::spray_bottle),
            (std::vector<std::string>{"body", "neck", "trigger"}));
  EXPECT_THROW(parse_enum<SyntheticCategory>("teapot"), UsageError);
}

TEST(Synthetic, CorrespondencesLieOnTheSurfaceAndMeanTheSamePlace) {
  for (int index : {0, 1, 2}) {
    const auto mug = make_synthetic_instance(SyntheticCategory::mug, 9, index);
    const auto gt = sample_correspondences(SyntheticCategory::mug, mug.shape_parameters, 400, 3);
    // On the surface: close to the part mesh's vertices (grid spacing ~ 1 cm on a 10 cm mug).
    for (int part = 0; part < 2; ++part) {
      const KdTree tree(mug.parts[static_cast<std::size_t>(part)].mesh.vertices);
      for (Eigen::Index i = 0; i < gt.points.rows(); ++i)
        if (gt.part[i] == part)
          EXPECT_LT(std::sqrt(tree.nearest(gt.points.row(i).transpose()).second), 0.015);
    }
    // The same row is the same semantic point: the handle's outermost point (u = 0.5) is at +x, beyond the
    // body.
    const Eigen::Vector3d outer =
        evaluate_surface(SyntheticCategory::mug, mug.shape_parameters, 1, 0.5, 0.25);
    EXPECT_GT(outer.x(), mug.shape_parameters[0]);
  }
}

TEST(Training, AHeldOutMugIsReconstructedBetterByTheSpaceThanByTheMean) {
  std::vector<TrainingInstance> instances;
  for (const auto& synthetic : make_synthetic_category(SyntheticCategory::mug, 9, 4))
    instances.push_back(instance_of(synthetic, 1200));
  const TrainingInstance held_out = instances.back();
  instances.pop_back();
  TrainingSettings settings;
  settings.canonical_points = 400;
  settings.target_points = 800;
  TrainingReport report;
  const CategoryModel model = train_category("mugs", instances, {"body", "handle"}, settings, &report);
  ASSERT_EQ(model.spaces.size(), 3u);
  EXPECT_EQ(model.holistic().dimensions(), 5);

  // Register the canonical onto the held-out mug as training would, then compare its field with the best
  // field inside the space and with the mean field alone.
  NonrigidCpdSettings cpd;
  cpd.beta = settings.beta;
  cpd.lambda = settings.lambda;
  cpd.outlier_weight = settings.outlier_weight;
  cpd.normalize = false;
  const Points target = model.normalization.apply(held_out.points);
  const auto result = register_nonrigid(model.canonical, target, cpd);
  const ShapeSpace& space = model.holistic();
  const Points displacement = result.moved - model.canonical;
  const Eigen::VectorXd latent = space.project_displacement(displacement);
  const double by_space = (space.deformed(latent) - result.moved).rowwise().norm().mean();
  const double by_mean =
      (space.deformed(Eigen::VectorXd::Zero(space.dimensions())) - result.moved).rowwise().norm().mean();
  EXPECT_LT(by_space, 0.8 * by_mean) << "space " << by_space << " mean " << by_mean;
}

TEST(Training, KeepsEachInstancesFieldAndLatentsAndReportsMonotoneProgressToTheEnd) {
  std::vector<TrainingInstance> instances;
  for (const auto& synthetic : make_synthetic_category(SyntheticCategory::mug, 4, 6))
    instances.push_back(instance_of(synthetic, 500));
  TrainingSettings settings;
  settings.canonical_points = 150;
  settings.target_points = 300;
  settings.latent_dimensions = 3;  // = K - 1: each instance's displacement lies inside the space
  std::vector<TrainingProgress> steps;
  std::vector<std::string> lines;
  TrainingReport report;  // asked for, so the instances' own labels are measured against propagated ones
  const CategoryModel model = train_category("mugs", instances, {"body", "handle"}, settings, &report,
                                             [&](const TrainingProgress& step) { steps.push_back(step); });
  train_category("mugs", instances, {"body", "handle"}, settings, &report,
                 [&](const std::string& line) { lines.push_back(line); });
  std::size_t unreported = 0;
  train_category("mugs", instances, {"body", "handle"}, settings, nullptr,
                 [&](const TrainingProgress& step) { unreported = step.total; });
  EXPECT_EQ(unreported, 15u);  // no report: instances with their own labels need no label CPD

  // K (1 + P) steps for 4 instances and 2 parts, one per instance held out to choose the seam weight and one
  // per label CPD (both all but the canonical), counted up by one, ending at 1; the line callback gets the
  // same lines.
  ASSERT_EQ(steps.size(), 18u);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_EQ(steps[i].total, 18u);
    EXPECT_EQ(steps[i].done, i + 1);
    if (i > 0) EXPECT_GT(steps[i].fraction(), steps[i - 1].fraction());
  }
  EXPECT_EQ(steps.back().fraction(), 1.0);
  ASSERT_EQ(lines.size(), steps.size());
  EXPECT_EQ(lines.front().rfind("cpd holistic", 0), 0u) << lines.front();
  EXPECT_EQ(std::count_if(lines.begin(), lines.end(),
                          [](const std::string& line) { return line.rfind("cpd labels", 0) == 0; }),
            3);

  // The holistic field of each instance is kept; its latent is the projection of its displacement G W_i.
  ASSERT_EQ(model.training_weights.rows(), 4);
  ASSERT_EQ(model.training_weights.cols(), 3 * model.canonical.rows());
  const ShapeSpace& space = model.holistic();
  ASSERT_EQ(space.training_latents.rows(), 4);
  ASSERT_EQ(space.training_latents.cols(), 3);
  for (int i = 0; i < 4; ++i) {
    const Points weights = model.training_weight_field(i);
    const Points displacement = apply_kernel(space.canonical, space.canonical, weights, space.beta);
    const Eigen::VectorXd latent = space.project_displacement(displacement);
    EXPECT_LT((latent.transpose() - space.training_latents.row(i)).norm(), 1e-9 * (1.0 + latent.norm()));
    // With q = K - 1 the space holds every training shape: its latent rebuilds the fit.
    EXPECT_LT((space.deformed(latent) - (space.canonical + displacement)).cwiseAbs().maxCoeff(), 1e-8);
    if (instances[static_cast<std::size_t>(i)].name == model.training.canonical)
      EXPECT_EQ(weights.cwiseAbs().maxCoeff(), 0.0);
  }
  // The instances lie apart: a mix-up of rows would fail the checks above.
  EXPECT_GT((space.training_latents.row(1) - space.training_latents.row(2)).norm(), 1e-3);
  for (const ShapeSpace& part : model.spaces) EXPECT_EQ(part.training_latents.rows(), 4);
}

int points_of_part(const CategoryModel& model, int part) {
  return static_cast<int>((model.canonical_part.array() == part).count());
}

// `count` synthetic mugs of `samples` points each, and training settings small enough for a unit test.
std::vector<TrainingInstance> synthetic_mugs(int count, int seed, int samples) {
  std::vector<TrainingInstance> instances;
  for (const auto& synthetic : make_synthetic_category(SyntheticCategory::mug, count, seed))
    instances.push_back(instance_of(synthetic, samples));
  return instances;
}

TrainingSettings small_settings(int canonical_points, int target_points, int latent_dimensions) {
  TrainingSettings settings;
  settings.canonical_points = canonical_points;
  settings.target_points = target_points;
  settings.latent_dimensions = latent_dimensions;
  return settings;
}

TEST(Training, EveryPartGetsItsFloorOfCanonicalPointsAndKeepsIt) {
  const std::vector<TrainingInstance> instances = synthetic_mugs(3, 4, 800);
  TrainingSettings settings = small_settings(100, 300, 2);
  settings.min_part_points = 0;
  const CategoryModel without = train_category("mugs", instances, {"body", "handle"}, settings);
  settings.min_part_points = 40;
  const CategoryModel with = train_category("mugs", instances, {"body", "handle"}, settings);
  // Sampling the whole leaves the handle below the floor (the test needs that to mean anything) ...
  ASSERT_LT(points_of_part(without, 1), 40);
  // ... the floor gives it 40 of its own points and leaves the body's as they were.
  EXPECT_EQ(points_of_part(with, 1), 40);
  EXPECT_EQ(with.space("handle").point_count(), 40);
  EXPECT_EQ(points_of_part(with, 0), points_of_part(without, 0));
  EXPECT_EQ(with.training.min_part_points, 40);
  EXPECT_EQ(with.training.canonical_points, with.canonical.rows());
}

TEST(Training, PartSpacesAgreeAtTheirSeamsOnTheirTrainingShapes) {
  const std::vector<TrainingInstance> instances = synthetic_mugs(5, 5, 1200);
  TrainingSettings settings = small_settings(400, 600, 3);
  const SeamGap agreeing = training_seam_gap(train_category("mugs", instances, {"body", "handle"}, settings));
  settings.seam_band = 0.0;  // the part CPDs' own fields
  const SeamGap apart = training_seam_gap(train_category("mugs", instances, {"body", "handle"}, settings));
  std::cerr << "synthetic mugs, seam gap at the training shapes: mean " << agreeing.mean << ", largest "
            << agreeing.max << " (without the band " << apart.mean << ", " << apart.max << ")\n";
  ASSERT_GT(agreeing.points, 0);
  EXPECT_LT(agreeing.mean, 0.007);  // measured 0.0047; 0.021 without the band
  EXPECT_GT(apart.mean, 3.0 * agreeing.mean);
  for (double band : {-0.1, 1.5, std::nan("")}) {
    settings.seam_band = band;
    EXPECT_THROW(train_category("mugs", instances, {"body", "handle"}, settings), UsageError) << band;
  }
}

TEST(Training, ChoosesTheCoupledSeamWeightOnHeldOutViewsAndRegistrationUsesIt) {
  const std::vector<TrainingInstance> instances = synthetic_mugs(4, 6, 500);
  TrainingSettings settings = small_settings(150, 300, 2);
  settings.seam_weight_candidates = {
      0.3, 100.0};  // far apart; neither is the default, which another must clearly beat
  const CategoryModel model = train_category("mugs", instances, {"body", "handle"}, settings);
  ASSERT_TRUE(model.training.seam_weight.has_value());
  std::map<double, double> errors;
  for (const SeamWeightTrial& trial : model.training.seam_weight_trials) errors[trial.weight] = trial.error;
  ASSERT_EQ(errors.size(), 2u) << model.training.seam_weight_choice;
  for (const auto& [weight, error] : errors) EXPECT_GT(error, 0.0) << weight;
  // The one with the lower mean error over the held-out instances' views is kept.
  const double best = errors.at(0.3) < errors.at(100.0) ? 0.3 : 100.0;
  EXPECT_EQ(*model.training.seam_weight, best) << model.training.seam_weight_choice;
  EXPECT_NE(errors.at(0.3), errors.at(100.0));  // the weights were really tried

  // Registration takes the model's unless asked for another.
  RegistrationSettings request;
  EXPECT_EQ(with_model_defaults(request, model).objective.seam_weight, best);
  request.objective.seam_weight = 7.0;
  EXPECT_EQ(with_model_defaults(request, model).objective.seam_weight, 7.0);

  // One weight is given, not chosen; fewer than three instances leave nothing to hold out.
  settings.seam_weight_candidates = {3.0};
  const CategoryModel given = train_category("mugs", instances, {"body", "handle"}, settings);
  EXPECT_EQ(given.training.seam_weight, 3.0);
  EXPECT_EQ(given.training.seam_weight_choice, "given");
  EXPECT_TRUE(given.training.seam_weight_trials.empty());
  settings.seam_weight_candidates = {1.0, 3.0, 10.0, 30.0};
  const CategoryModel two =
      train_category("mugs", {instances[0], instances[1]}, {"body", "handle"}, settings);
  EXPECT_EQ(two.training.seam_weight, 10.0);
  EXPECT_NE(two.training.seam_weight_choice.find("too few instances"), std::string::npos);
  // A model without parts has no seam: registration falls back to the default.
  std::vector<TrainingInstance> whole = instances;
  for (TrainingInstance& instance : whole) instance.part.resize(0);
  const CategoryModel plain = train_category("mugs", whole, {}, settings);
  EXPECT_FALSE(plain.training.seam_weight.has_value());
  EXPECT_EQ(with_model_defaults({}, plain).objective.seam_weight, kDefaultSeamWeight);
}

TEST(Training, APartWithoutCanonicalPointsIsRefusedNamingIt) {
  const auto synthetic = make_synthetic_category(SyntheticCategory::mug, 2, 1);
  std::vector<TrainingInstance> instances = {instance_of(synthetic[0], 300), instance_of(synthetic[1], 300)};
  TrainingSettings settings;
  settings.canonical = instances[0].name;
  try {  // "lid" is a part of the category, but no point of the canonical carries it
    train_category("m", instances, {"body", "handle", "lid"}, settings);
    FAIL() << "a part without canonical points was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("part 'lid' has no canonical point after sampling"),
              std::string::npos)
        << error.what();
  }
}

TEST(Training, RefusesTooFewInstancesAndBadLabels) {
  const auto synthetic = make_synthetic_category(SyntheticCategory::mug, 2, 1);
  std::vector<TrainingInstance> one = {instance_of(synthetic[0], 300)};
  EXPECT_THROW(train_category("m", one, {"body", "handle"}, {}), InputError);
  std::vector<TrainingInstance> bad = {instance_of(synthetic[0], 300), instance_of(synthetic[1], 300)};
  bad[1].part[0] = 5;
  EXPECT_THROW(train_category("m", bad, {"body", "handle"}, {}), InputError);
}

}  // namespace
}  // namespace partreg::core
