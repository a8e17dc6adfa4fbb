// The evaluation and training tools of the app: partial view, perturbation, training with the edited labels.
#include <gtest/gtest.h>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/io/labels_file.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/script.hpp"
#include "ui/ui_fixtures.hpp"

namespace partreg::ui {
namespace {

void run(AppState& state, const std::string& script) {
  for (const Command& command : parse_script(script)) execute(state, command);
}

TEST(Tools, APartialViewKeepsTheNearSideAndSetsTheViewpoint) {
  AppState state;
  run(state, "load " + testing::observed_cloud_path().string());
  const core::Points full = state.registration.observed;
  ASSERT_FALSE(state.registration.viewpoint);
  run(state, "partial_view 0 count=12");
  const core::Points& seen = state.registration.observed;
  EXPECT_LT(seen.rows(), 0.75 * full.rows());
  EXPECT_GT(seen.rows(), 0.2 * full.rows());
  ASSERT_TRUE(state.registration.viewpoint);
  // The seen points lie on the camera's side: their mean is nearer the viewpoint than the full set's mean.
  const Eigen::Vector3d eye = *state.registration.viewpoint;
  EXPECT_LT((seen.colwise().mean().transpose() - eye).norm(),
            (full.colwise().mean().transpose() - eye).norm());
  EXPECT_FALSE(execute_reporting(state, make_command("partial_view", {"12"}, {{"count", "12"}})));
  EXPECT_FALSE(execute_reporting(state, make_command("partial_view", {"0"}, {{"count", "40"}})));
}

TEST(Tools, ARotationMovesTheObservationAndItsViewpointTogether) {
  AppState state;
  run(state, "load " + testing::observed_cloud_path().string() + "\npartial_view 3 count=12");
  const core::Points before = state.registration.observed;
  const Eigen::Vector3d eye = *state.registration.viewpoint;
  const Eigen::Vector3d centre = (before.colwise().minCoeff() + before.colwise().maxCoeff()).transpose() / 2;
  run(state, "perturb rotation 0.39 seed=4");
  EXPECT_EQ(state.registration.observed.rows(), before.rows());
  // A rigid motion: distances to the viewpoint are kept (the camera moved with the object).
  for (Eigen::Index i = 0; i < before.rows(); i += 97)
    EXPECT_NEAR((state.registration.observed.row(i).transpose() - *state.registration.viewpoint).norm(),
                (before.row(i).transpose() - eye).norm(), 1e-9);
  EXPECT_NEAR((*state.registration.viewpoint - centre).norm(), (eye - centre).norm(), 1e-9);
  EXPECT_GT((*state.registration.viewpoint - eye).norm(), 0.1 * (eye - centre).norm());
  run(state, "perturb outliers 0.2");
  EXPECT_EQ(state.registration.observed.rows(), before.rows() + std::llround(0.2 * double(before.rows())));
  EXPECT_FALSE(execute_reporting(state, make_command("perturb", {"shear", "0.1"})));
  EXPECT_FALSE(execute_reporting(state, make_command("perturb", {"rotation", "7"})));
}

TEST(Tools, TrainingUsesTheLabelledMeshAsTheCanonical) {
  // A dataset of four synthetic mugs (one mesh file each); mug 0 is labelled body/handle in the app.
  const std::filesystem::path folder = testing::mug_dataset("train_dataset", 4);
  Eigen::VectorXi merged_part;
  const core::Mesh merged = testing::merged_mug(0, &merged_part);
  // Reading drops degenerate faces: label the faces as read, each by the part of the nearest original face.
  const core::Mesh read = io::read_mesh(folder / "mug_0.obj");
  auto centroids = [](const core::Mesh& mesh) {
    core::Points c(mesh.faces.rows(), 3);
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
      c.row(f) = (mesh.vertices.row(mesh.faces(f, 0)) + mesh.vertices.row(mesh.faces(f, 1)) +
                  mesh.vertices.row(mesh.faces(f, 2))) /
                 3;
    return c;
  };
  const core::KdTree original(centroids(merged));
  const core::Points read_centroids = centroids(read);
  io::PartLabels labels;
  labels.part_index("body");
  labels.part_index("handle");
  labels.labels.resize(read.faces.rows());
  for (Eigen::Index f = 0; f < read.faces.rows(); ++f)
    labels.labels[f] = merged_part[original.nearest(read_centroids.row(f).transpose()).first];
  labels.source = "mug_0.obj";
  io::write_labels_file(folder.parent_path() / "train_labels.json", labels);

  AppState state;
  run(state, "load " + (folder / "mug_0.obj").string() + "\nload_labels " +
                 (folder.parent_path() / "train_labels.json").string());
  const std::string model = (folder.parent_path() / "trained.prm").string();
  run(state, "train " + folder.string() + " out=" + model);
  ASSERT_TRUE(state.shapes.loaded());
  EXPECT_EQ(state.shapes.model->training.canonical, "mug_0");
  EXPECT_EQ(state.shapes.model->part_names, (std::vector<std::string>{"body", "handle"}));
  EXPECT_EQ(state.shapes.model->spaces.size(), 3u);  // holistic, body, handle
  EXPECT_TRUE(std::filesystem::exists(model));
  // An unlabelled face refuses training and leaves the loaded model as it was.
  run(state, "load " + (folder / "mug_0.obj").string());
  EXPECT_FALSE(execute_reporting(state, make_command("train", {folder.string()}, {{"out", model + ".2"}})));
  EXPECT_FALSE(std::filesystem::exists(model + ".2"));
}

TEST(Tools, ATrainingJobReportsMonotoneProgressToTheEndAndItsModelLoads) {
  const std::filesystem::path folder = testing::mug_dataset("job_dataset", 3);
  const std::string model = (testing::ui_fixture_folder() / "job.prm").string();
  std::filesystem::remove(model);
  AppState state;
  const TrainingJob job = prepare_training(state, make_command("train", {folder.string()}, {{"out", model}}));
  std::vector<core::TrainingProgress> steps;
  const std::string summary = job.run([&](const core::TrainingProgress& step) { steps.push_back(step); });
  // First "reading" at 0, then K (1 + P) = 3 steps for 3 mugs without parts, each further than the last.
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_EQ(steps.front().fraction(), 0.0);
  for (std::size_t i = 1; i < steps.size(); ++i) EXPECT_GT(steps[i].fraction(), steps[i - 1].fraction());
  EXPECT_EQ(steps.back().fraction(), 1.0);
  EXPECT_FALSE(state.shapes.loaded());  // running the job touched no state
  ASSERT_TRUE(std::filesystem::exists(model));
  EXPECT_EQ(apply_training(state, job, summary).message, summary);
  ASSERT_TRUE(state.shapes.loaded());
  EXPECT_EQ(state.shapes.model->training.instances.size(), 3u);
  // A folder that does not exist is refused before any work.
  EXPECT_THROW(prepare_training(state, make_command("train", {(folder / "nowhere").string()})), InputError);
}

}  // namespace
}  // namespace partreg::ui
