// Free space on a rendered table top: a held-out synthetic mug stands with its handle behind its body, hidden
// from the camera. The true pose keeps out of the space the camera saw empty; the same mug turned half about
// its up axis brings the handle in front of the body the camera measured, and reads a high violation share.
// The pose search scored with free space puts the handle where the camera could not have seen it.
#include <gtest/gtest.h>

#include <iostream>

#include "partreg/core/kdtree.hpp"
#include "partreg/core/synthetic.hpp"
#include "partreg/core/training.hpp"
#include "partreg/scene/depth_render.hpp"
#include "partreg/scene/scene_input.hpp"
#include "partreg/scene/scene_registration.hpp"
#include "partreg/scene/segmentation.hpp"
#include "partreg/scene/table_scene.hpp"
#include "support/test_shapes.hpp"

namespace partreg::scene {
namespace {

constexpr int kHandle = 1;  // the synthetic mug's parts: body, handle

core::Mesh merged(const std::vector<core::SyntheticPart>& parts) {
  core::Mesh mesh;
  for (const core::SyntheticPart& part : parts) {
    const Eigen::Index offset = mesh.vertices.rows();
    mesh.vertices.conservativeResize(offset + part.mesh.vertices.rows(), 3);
    mesh.vertices.bottomRows(part.mesh.vertices.rows()) = part.mesh.vertices;
    mesh.faces.conservativeResize(mesh.faces.rows() + part.mesh.faces.rows(), 3);
    mesh.faces.bottomRows(part.mesh.faces.rows()) = part.mesh.faces.array() + static_cast<int>(offset);
  }
  return mesh;
}

core::Points transformed(const core::Points& points, const Eigen::Matrix4d& T) {
  return (points * T.topLeftCorner<3, 3>().transpose()).rowwise() + T.topRightCorner<3, 1>().transpose();
}

struct MugScene {
  core::CategoryModel model;
  core::Points truth;         ///< the held-out mug's surface samples in the camera frame (m)
  core::Points handle_truth;  ///< its handle's samples
  Eigen::Vector3d up;         ///< the table's normal (camera frame)
  Eigen::Vector3d body_centre;  ///< the mean of its body's samples (camera frame)
  SceneView view;
};

// Seven synthetic mugs train the model; the eighth stands on the table, turned so its handle points away
// from the camera.
MugScene make_scene() {
  MugScene scene;
  const std::vector<core::SyntheticInstance> mugs = core::make_synthetic_category(core::SyntheticCategory::mug, 8, 21);
  std::vector<core::TrainingInstance> training;
  for (std::size_t i = 0; i + 1 < mugs.size(); ++i) {
    const core::SurfaceSamples samples =
        core::sample_correspondences(core::SyntheticCategory::mug, mugs[i].shape_parameters, 1500, 5);
    training.push_back({mugs[i].name, samples.points, samples.part, {}, {}});
  }
  core::TrainingSettings settings;
  settings.canonical_points = 600;
  settings.seam_weight_candidates = {core::kDefaultSeamWeight};
  scene.model = core::train_category("mugs", training, {"body", "handle"}, settings);

  const core::SurfaceSamples held =
      core::sample_correspondences(core::SyntheticCategory::mug, mugs.back().shape_parameters, 1500, 5);
  core::Mesh mesh = merged(mugs.back().parts);
  const double size = core::bounding_box_diagonal(mesh.vertices);  // its own size: the model's units are metres
  // Where the layout puts the camera, in the mug's frame; then the mug turned about its up axis (+y) so the
  // handle points away from it.
  const TableScene first = lay_out_table({TableObject{mesh, Eigen::Vector3d::UnitY(), size}});
  const Eigen::Vector3d camera = first.objects[0].T_camera_object.inverse().topRightCorner<3, 1>();
  Eigen::Vector3d handle = Eigen::Vector3d::Zero(), body = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < held.points.rows(); ++i)
    (held.part(i) == kHandle ? handle : body) += held.points.row(i).transpose();
  const int handle_count = static_cast<int>((held.part.array() == kHandle).count());
  handle /= handle_count;
  body /= static_cast<double>(held.points.rows() - handle_count);
  const Eigen::Vector3d out = handle - body, away = body - camera;
  // A turn by theta about +y takes the horizontal angle atan2(z, x) to atan2(z, x) - theta.
  const double theta = std::atan2(out.z(), out.x()) - std::atan2(away.z(), away.x());
  const Eigen::Matrix3d R = testing::rotation(theta, Eigen::Vector3d::UnitY());
  mesh.vertices = mesh.vertices * R.transpose();
  const TableScene table = lay_out_table({TableObject{mesh, Eigen::Vector3d::UnitY(), size}});
  Eigen::Matrix4d T_camera_held = table.objects[0].T_camera_object;
  T_camera_held.topLeftCorner<3, 3>() *= R;
  scene.truth = transformed(held.points, T_camera_held);
  std::vector<int> handle_rows;
  for (Eigen::Index i = 0; i < held.part.size(); ++i)
    if (held.part(i) == kHandle) handle_rows.push_back(static_cast<int>(i));
  scene.handle_truth = core::select_rows(scene.truth, handle_rows);
  scene.body_centre = T_camera_held.topLeftCorner<3, 3>() * body + T_camera_held.topRightCorner<3, 1>();
  scene.up = table.plane.head<3>();
  const Intrinsics k;
  scene.view = depth_view(render_depth({table.objects[0].mesh, table.table}, k).depth, k);
  return scene;
}

const MugScene& mug_scene() {
  static const MugScene scene = make_scene();
  return scene;
}

// The points turned half about the table's normal through the body's centre: the handle to the other side.
core::Points turned_about_up(const core::Points& points, const MugScene& scene) {
  const Eigen::RowVector3d centre = scene.body_centre.transpose();
  const Eigen::Matrix3d R = testing::rotation(M_PI, scene.up);
  return ((points.rowwise() - centre) * R.transpose()).rowwise() + centre;
}

TEST(FreeSpaceScene, TheTruePoseKeepsOutOfFreeSpaceAndTheHandleTurnedIntoViewDoesNot) {
  const MugScene& scene = mug_scene();
  const auto free = free_space_of(scene.view);
  ASSERT_TRUE(free);
  const double right = free->violation_share(scene.truth);
  const double wrong = free->violation_share(turned_about_up(scene.truth, scene));
  std::cerr << "violation share: true pose " << right << ", handle turned into view " << wrong << "\n";
  EXPECT_LT(right, 0.02);
  EXPECT_GT(wrong, 0.10);
}

double handle_error(const core::RegistrationResult& result, const core::CategoryModel& model,
                    const core::Points& handle_truth) {
  std::vector<int> rows;
  for (Eigen::Index i = 0; i < result.part.size(); ++i)
    if (result.part(i) == kHandle) rows.push_back(static_cast<int>(i));
  const core::Points handle = core::select_rows(result.deformed, rows);
  (void)model;
  return (handle.colwise().mean() - handle_truth.colwise().mean()).norm();
}

TEST(FreeSpaceScene, ThePoseSearchWithFreeSpaceKeepsTheHiddenHandleHidden) {
  const MugScene& scene = mug_scene();
  const SceneCut cut = cut_scene(scene.view);
  ASSERT_TRUE(cut.free_space);
  core::RegistrationSettings settings;
  settings.refinement.enabled = false;
  core::RegistrationSettings without = settings;
  without.initialisation.free_space_weight = 0.0;
  const core::RegistrationResult blind = register_cut(scene.model, cut, without);
  const core::RegistrationResult seeing = register_cut(scene.model, cut, settings);
  std::cerr << "without free space: violation " << *blind.figures.free_space_violation << ", handle off by "
            << handle_error(blind, scene.model, scene.handle_truth) << " m; with: "
            << *seeing.figures.free_space_violation << ", "
            << handle_error(seeing, scene.model, scene.handle_truth) << " m\n";
}

}  // namespace
}  // namespace partreg::scene
