// Tests on the real object data in ../shared/data (skipped, saying so, where it is absent).
#include "support/shared_data.hpp"

#include <gtest/gtest.h>

#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "support/test_shapes.hpp"

namespace partreg {
namespace {

using testing::shared_data;

TEST(SharedData, EveryFileReads) {
  const auto root = testing::shared_data_dir();
  PARTREG_REQUIRE_SHARED_DATA(root);
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    const std::string extension = entry.path().extension().string();
    if (!entry.is_regular_file() || (extension != ".pcd" && extension != ".obj" && extension != ".ply"))
      continue;
    SCOPED_TRACE(entry.path().string());
    if (io::is_mesh_file(entry.path())) {
      const core::Mesh mesh = io::read_mesh(entry.path());
      EXPECT_GT(mesh.faces.rows(), 0);
      EXPECT_TRUE(mesh.vertices.allFinite());
    } else {
      const io::CloudFile cloud = io::read_cloud_file(entry.path());
      EXPECT_GT(cloud.cloud.points.rows(), 100);
      EXPECT_TRUE(cloud.cloud.points.allFinite());
    }
    ++files;
  }
  EXPECT_GE(files, 40);  // 11 drills, 20 kettle parts, 10 mugs, 8 bowls, 8 bottles, 7 spatulas
}

void expect_rigid_recovery(const core::Points& shape) {
  const double diagonal = core::bounding_box_diagonal(shape);
  const Eigen::Matrix3d R = testing::rotation(50.0 * M_PI / 180.0, {0.3, 1.0, 0.2});
  const Eigen::Vector3d t = Eigen::Vector3d(0.1, -0.05, 0.08) * diagonal;
  std::mt19937_64 generator(11);
  std::normal_distribution<double> noise(0.0, 0.003 * diagonal);
  core::Points target = (shape * R.transpose()).rowwise() + t.transpose();
  for (Eigen::Index i = 0; i < target.size(); ++i) target.data()[i] += noise(generator);
  // 20% outliers, uniform in the bounding box
  const Eigen::Index outliers = shape.rows() / 5;
  core::Points with_outliers(target.rows() + outliers, 3);
  with_outliers.topRows(target.rows()) = target;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Eigen::RowVector3d low = target.colwise().minCoeff(), high = target.colwise().maxCoeff();
  for (Eigen::Index i = 0; i < outliers; ++i)
    for (int d = 0; d < 3; ++d)
      with_outliers(target.rows() + i, d) = low[d] + uniform(generator) * (high[d] - low[d]);
  core::RigidCpdSettings settings;
  settings.outlier_weight = 0.2;
  const auto result = core::register_rigid(shape, with_outliers, settings);
  EXPECT_LT(testing::rotation_error_deg(result.rotation, R), 1.0);
  EXPECT_LT((result.translation - t).norm(), 0.01 * diagonal);
  ASSERT_GT(testing::rotation_error_deg(Eigen::Matrix3d::Identity(), R), 10.0);
}

TEST(SharedData, RigidCpdRecoversAPoseOfARealDrill) {
  const auto path = shared_data("drills/drill_3.pcd");
  PARTREG_REQUIRE_SHARED_DATA(path);
  expect_rigid_recovery(io::read_cloud_file(path).cloud.points);
}

TEST(SharedData, RigidCpdRecoversAPoseOfASampledShapeNetMug) {
  const auto path = shared_data("mugs/1a97f3c83016abca21d0de04f408950f.obj");
  PARTREG_REQUIRE_SHARED_DATA(path);
  expect_rigid_recovery(io::read_as_cloud(path, 1000, 1).points);
}

TEST(SharedData, NonrigidCpdBringsOneDrillOntoAnother) {
  const auto a = shared_data("drills/drill_1.pcd"), b = shared_data("drills/drill_2.pcd");
  PARTREG_REQUIRE_SHARED_DATA(a);
  const core::Points source = io::read_cloud_file(a).cloud.points,
                     target = io::read_cloud_file(b).cloud.points;
  const core::KdTree tree(target);
  auto mean_distance = [&](const core::Points& points) {
    std::vector<int> index;
    Eigen::VectorXd squared;
    tree.nearest_all(points, index, squared);
    return squared.cwiseSqrt().mean();
  };
  const auto result = core::register_nonrigid(source, target, {});
  const double before = mean_distance(source), after = mean_distance(result.moved);
  EXPECT_LT(after, 0.5 * before) << "before " << before << " after " << after;
  // Two different drills under a very smooth field (beta = 2): measured 2.3% of the diagonal.
  EXPECT_LT(after, 0.03 * core::bounding_box_diagonal(target));
}

TEST(SharedData, NonrigidCpdReachesASmoothlyDisplacedRealDrill) {
  const auto path = shared_data("drills/drill_5.pcd");
  PARTREG_REQUIRE_SHARED_DATA(path);
  const core::Points source = io::read_cloud_file(path).cloud.points;
  const double diagonal = core::bounding_box_diagonal(source);
  // A smooth bend and bulge of about 5% of the diagonal, in normalised coordinates of the drill.
  const core::Normalization frame = core::Normalization::fit(source);
  core::Points normalised = frame.apply(source);
  for (Eigen::Index i = 0; i < normalised.rows(); ++i) {
    const double x = normalised(i, 0), y = normalised(i, 1), z = normalised(i, 2);
    normalised.row(i) += Eigen::RowVector3d(0.15 * z, 0.18 * std::sin(2.0 * x), 0.24 * x * x + 0.09 * y);
  }
  const core::Points target = frame.undo(normalised);
  core::NonrigidCpdSettings settings;
  settings.beta = 0.5;
  settings.lambda = 3.0;
  settings.outlier_weight = 0.0;
  settings.solver = core::NonrigidCpdSettings::Solver::exact;
  const auto exact = core::register_nonrigid(source, target, settings);
  settings.solver = core::NonrigidCpdSettings::Solver::fast;
  const auto fast = core::register_nonrigid(source, target, settings);
  const double error = testing::mean_row_distance(fast.moved, target) / diagonal;
  std::cerr << "real drill: mean point error " << error << " of the diagonal (undeformed "
            << testing::mean_row_distance(source, target) / diagonal << "), fast vs exact "
            << testing::mean_row_distance(fast.moved, exact.moved) / diagonal << "\n";
  EXPECT_LT(error, 0.01);
  EXPECT_LT(testing::mean_row_distance(fast.moved, exact.moved), 0.005 * diagonal);
  ASSERT_GT(testing::mean_row_distance(source, target), 0.02 * diagonal);  // the undeformed source would fail
}

TEST(SharedData, KettleLabelsPropagateToEveryOtherKettle) {
  const auto path = shared_data("kettles");
  PARTREG_REQUIRE_SHARED_DATA(path);
  const io::Dataset dataset = io::read_dataset(path);
  core::TrainingReport report;
  const auto model = core::train_category(dataset.name, dataset.instances, dataset.part_names, {}, &report);
  ASSERT_EQ(report.label_agreement.size(), dataset.instances.size() - 1);  // every kettle but the canonical
  double mean = 0.0;
  int with_shared_surface = 0;
  for (const auto& [instance, agreement] : report.label_agreement) {
    // Measured 93.9-98.1%, 96.4% on average, where another part lying on a point's own (a lid on its body's
    // top) may name it; 89.5-97.9% (94.5%) through the holistic CPD's finer fit (docs/training.md). The issue
    // asks 95%.
    EXPECT_GT(agreement.by_surface.at("all"), 0.92) << instance;
    for (const auto& [part, fraction] : agreement.by_surface)
      EXPECT_GT(fraction, 0.75) << instance << " " << part;
    EXPECT_GE(agreement.by_surface.at("all"), agreement.by_sampled_part.at("all")) << instance;
    if (agreement.shared_surface > 0.05) {
      ++with_shared_surface;
      // Where a lid lies on the body a point's sampled part is a coin's toss: the figures must differ there.
      EXPECT_GT(agreement.by_surface.at("all"), agreement.by_sampled_part.at("all") + 0.03) << instance;
    }
    mean += agreement.by_surface.at("all") / static_cast<double>(report.label_agreement.size());
  }
  EXPECT_GT(mean, 0.95);
  EXPECT_GE(with_shared_surface, 2);  // measured 10-16% of kettles 3, 4 and 5 (0.6% of kettle 1)
  EXPECT_EQ(model.spaces.size(), 5u);

  // The part spaces agree at their seams on the shapes they were trained on
  // (core/core/src/space/seam_agreement.hpp); the part CPDs' own fields (seam_band 0, the paper's training)
  // put the parts of the same kettle apart.
  core::TrainingSettings unrefitted;
  unrefitted.seam_band = 0.0;
  const double agreeing = core::training_seam_gap(model).mean;
  const double apart =
      core::training_seam_gap(core::train_category(dataset.name, dataset.instances, dataset.part_names, unrefitted))
          .mean;
  std::cerr << "kettle part spaces at the training latents: mean seam gap " << agreeing
            << " of the diagonal (part CPDs' own fields: " << apart << ")\n";
  EXPECT_LT(agreeing, 0.01);  // measured 0.0063 (0.046 without the seam band)
  EXPECT_GT(apart, 0.02);
}

}  // namespace
}  // namespace partreg
