#include "partreg/core/training.hpp"

#include <gtest/gtest.h>

#include "partreg/core/errors.hpp"
#include "partreg/core/kdtree.hpp"
#include "partreg/core/synthetic.hpp"

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
  EXPECT_THROW(parse_synthetic_category("teapot"), UsageError);
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
