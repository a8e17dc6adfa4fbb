// Free space on a rendered table top: a held-out synthetic mug stands with its handle behind its body, hidden
// from the camera. The true pose keeps out of the space the camera saw empty; the same mug turned half about
// its up axis brings the handle in front of the body the camera measured, and reads a high violation share.
// The pose search scored with free space puts the handle where the camera could not have seen it.
#include <gtest/gtest.h>

#include <iostream>

#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/scene/depth_render.hpp"
#include "partreg/scene/scene_input.hpp"
#include "partreg/scene/scene_registration.hpp"
#include "partreg/scene/segmentation.hpp"
#include "partreg/scene/table_scene.hpp"
#include "support/shared_data.hpp"
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
  core::Points truth;           ///< the held-out mug's surface samples in the camera frame (m)
  core::Points handle_truth;    ///< its handle's samples
  Eigen::Vector3d up;           ///< the table's normal (camera frame)
  Eigen::Vector3d body_centre;  ///< the mean of its body's samples (camera frame)
  SceneView view;
};

// Seven synthetic mugs train the model; the eighth stands on the table, turned so its handle points away
// from the camera.
MugScene make_scene() {
  MugScene scene;
  const std::vector<core::SyntheticInstance> mugs =
      core::make_synthetic_category(core::SyntheticCategory::mug, 8, 21);
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
  const double size =
      core::bounding_box_diagonal(mesh.vertices);  // its own size: the model's units are metres
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

// How far the registered handle's centre lies from the true one's (m).
double handle_error(const core::RegistrationResult& result, const core::Points& handle_truth) {
  std::vector<int> rows;
  for (Eigen::Index i = 0; i < result.part.size(); ++i)
    if (result.part(i) == kHandle) rows.push_back(static_cast<int>(i));
  const core::Points handle = core::select_rows(result.deformed, rows);
  return (handle.colwise().mean() - handle_truth.colwise().mean()).norm();
}

TEST(FreeSpaceScene, ThePoseSearchWithFreeSpaceKeepsTheHiddenHandleHidden) {
  const MugScene& scene = mug_scene();
  const SceneCut cut = cut_scene(scene.view);
  ASSERT_TRUE(cut.free_space);
  core::RegistrationSettings blind_settings;
  blind_settings.refinement.enabled = false;  // the pose is what free space decides
  core::RegistrationSettings settings = blind_settings;
  settings.initialisation.free_space_weight = 10.0;  // off by default (registration_settings.hpp)
  const core::RegistrationResult blind = register_cut(scene.model, cut, blind_settings);
  const core::RegistrationResult seeing = register_cut(scene.model, cut, settings);
  ASSERT_TRUE(blind.figures.free_space_violation && seeing.figures.free_space_violation);
  const double blind_error = handle_error(blind, scene.handle_truth);
  const double seeing_error = handle_error(seeing, scene.handle_truth);
  std::cerr << "without free space: violation " << *blind.figures.free_space_violation << ", handle off by "
            << blind_error << " m; with: " << *seeing.figures.free_space_violation << ", " << seeing_error
            << " m\n";
  // Measured: without free space the handle stood where the camera saw the body and the table (violation
  // 0.044 with the scene cut's 0.04 m clusters, 0.106 with 0.02 m; handle 0.106 m off); with it, hidden
  // behind the body (0.003, 0.048 m: behind the body it may turn unseen).
  EXPECT_LT(*seeing.figures.free_space_violation, 0.02);
  EXPECT_LT(seeing_error, 0.06);
  EXPECT_GT(*blind.figures.free_space_violation, 5.0 * *seeing.figures.free_space_violation);
  EXPECT_GT(*blind.figures.free_space_violation, 0.03);
  EXPECT_GT(blind_error, 0.08);
}

// A real ShapeNet mug (0.12 m) on the table at six seeded yaws: its true surface, and the same turned about
// the table's normal through its centre, the wrong answers a pose search weighs. Measured: the truth 0% on
// every view; a quarter turn 1.0% to 7.8%, half a turn 2.7% to 16.9%, the worse of the two 6.8% to 16.9%. A
// turn that hides a handle the camera saw is not in free space (the observed points refute it, not the empty
// space): only the turn that brings it where the camera saw the table or the body is.
TEST(FreeSpaceScene, ARealMugsTruthKeepsOutOfFreeSpaceAndItsTurnsDoNot) {
  const std::filesystem::path path = testing::shared_data("mugs/5c48d471200d2bf16e8a121e6886e18d.obj");
  PARTREG_REQUIRE_SHARED_DATA(path);
  const core::Mesh mug = io::read_mesh(path);
  const Intrinsics k;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    TableLayout layout;
    layout.seed = seed;
    const TableScene table = lay_out_table({TableObject{mug, Eigen::Vector3d::UnitY(), 0.12}}, layout);
    const auto free =
        free_space_of(depth_view(render_depth({table.objects[0].mesh, table.table}, k).depth, k));
    const core::Points truth = core::sample_surface(table.objects[0].mesh, 3000, seed).points;
    const Eigen::RowVector3d centre = table.objects[0].T_camera_object.topRightCorner<3, 1>().transpose();
    const auto turned = [&](double angle) {
      const Eigen::Matrix3d R = testing::rotation(angle, table.plane.head<3>());
      return core::Points(((truth.rowwise() - centre) * R.transpose()).rowwise() + centre);
    };
    const double right = free->violation_share(truth), quarter = free->violation_share(turned(M_PI / 2)),
                 half = free->violation_share(turned(M_PI));
    std::cerr << "seed " << seed << ": truth " << right << ", quarter turn " << quarter << ", half turn "
              << half << "\n";
    EXPECT_LT(right, 0.01);
    EXPECT_GT(std::max(quarter, half), 0.05);
  }
}

}  // namespace
}  // namespace partreg::scene
