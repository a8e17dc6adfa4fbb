#include "partreg/scene_eval/depth_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/eval/perturbation.hpp"
#include "partreg/scene/scene_input.hpp"
#include "partreg/scene/scene_registration.hpp"
#include "partreg/scene/segmentation.hpp"

namespace partreg::scene_eval {
namespace {

bool has_mesh(const core::TrainingInstance& instance) { return instance.mesh.faces.rows() > 0; }

// One rendered scene and what the held-out instance (object 0) is in it.
struct RenderedScene {
  scene::RenderedDepth rendered;
  scene::PixelMask mask;  // the held-out instance's pixels (first surface hit)
  double metres_per_unit = 1.0;
  Eigen::Isometry3d T_camera_object;  // the held-out instance's frame -> camera frame, in its data units
};

// The depth as a 16-bit PNG stores it (whole depth_scale units, 0 beyond 65535), so that the scene is
// exactly what `register --depth` would read from `partreg scene`'s depth.png.
scene::DepthImage as_stored(scene::DepthImage depth, double depth_scale) {
  for (float& metres : depth.metres) {
    const double units = std::round(double(metres) * depth_scale);
    metres = units > 0 && units <= 65535 ? float(units / depth_scale) : 0.0f;
  }
  return depth;
}

RenderedScene render_scene(const DepthSceneSettings& settings, const eval::EvalInput& input,
                           std::size_t held_out, const std::vector<std::size_t>& neighbours,
                           const Eigen::Vector3d& up, int job, std::uint64_t seed) {
  const core::Mesh& mesh = input.instances[held_out].mesh;
  RenderedScene out;
  out.T_camera_object = Eigen::Isometry3d::Identity();
  out.metres_per_unit = settings.object_size / core::bounding_box_diagonal(mesh.vertices);
  std::vector<scene::TableObject> objects = {{mesh, up, settings.object_size}};
  for (std::size_t n : neighbours) {
    const core::Mesh& other = input.instances[n].mesh;
    objects.push_back({other, up, out.metres_per_unit * core::bounding_box_diagonal(other.vertices)});
  }
  scene::TableLayout layout = settings.layout;
  layout.elevation_degrees = settings.elevations_degrees[job % settings.elevations_degrees.size()];
  layout.seed = seed;
  const scene::TableScene table = scene::lay_out_table(objects, layout);
  std::vector<core::Mesh> meshes;
  for (const scene::PlacedObject& placed : table.objects) meshes.push_back(placed.mesh);
  meshes.push_back(table.table);
  scene::SensorSettings sensor = settings.sensor;
  sensor.seed = seed;
  out.rendered = scene::render_depth(meshes, settings.intrinsics, sensor);
  out.rendered.depth = as_stored(out.rendered.depth, settings.intrinsics.depth_scale);
  out.mask = scene::surface_mask(out.rendered, 0);
  // The placed pose is s R x + t (metres); in data units of the camera frame it is R x + t / s.
  const Eigen::Matrix4d& T = table.objects.front().T_camera_object;
  out.T_camera_object.linear() = T.topLeftCorner<3, 3>() / out.metres_per_unit;
  out.T_camera_object.translation() = T.topRightCorner<3, 1>() / out.metres_per_unit;
  return out;
}

// The cut's pixels against the object's measured pixels: intersection over union, and the share of the cut
// on the object.
eval::SceneCutScore score_cut(eval::CutKind kind, const scene::CameraPoints& cut,
                              const RenderedScene& scene) {
  const std::vector<float>& depth = scene.rendered.depth.metres;
  std::size_t object = 0, common = 0;
  for (std::size_t p = 0; p < depth.size(); ++p) object += scene.mask.selected[p] && depth[p] > 0;
  for (int pixel : cut.pixel) common += pixel >= 0 && scene.mask.selected[pixel] && depth[pixel] > 0;
  const std::size_t either = cut.pixel.size() + object - common;
  return {kind, either > 0 ? double(common) / double(either) : 0.0,
          cut.pixel.empty() ? 0.0 : double(common) / double(cut.pixel.size())};
}

// The cut in the model's data units (the camera stays at the origin).
scene::SceneCut in_units(scene::SceneCut cut, double metres_per_unit) {
  cut.object.points /= metres_per_unit;
  cut.plane_points /= metres_per_unit;
  cut.plane[3] /= metres_per_unit;
  return cut;
}

// What every row of one cut shares: the truth moved into the camera frame (data units).
struct CutTruth {
  const core::KdTree* tree;
  const core::Points* correspondents;  // null: unknown
  const eval::TestedInstance* tested;
};

eval::EvalRow registered_row(const core::CategoryModel& model, const eval::EvalSettings& settings,
                             const DepthSceneSettings& scenes, const scene::SceneCut& cut,
                             core::Variant variant, const CutTruth& truth) {
  core::RegistrationSettings registration = settings.registration;
  registration.variant = variant;
  const core::RegistrationResult result =
      scene::register_cut(model, cut, registration, scenes.cut.registration);
  const Eigen::VectorXi* truth_part = truth.tested->truth_part;
  const bool truth_has_parts =
      !model.part_names.empty() && truth_part && truth_part->size() == truth.tested->truth->rows();
  eval::EvalRow row;
  row.errors = core::measure_against_truth(result.deformed, result.part, model.part_names, *truth.tree,
                                           truth.tested->diagonal, truth.correspondents,
                                           truth_has_parts ? truth_part : nullptr);
  // Correspondences are the material points' (as the protocol's own rows measure them).
  if (truth.correspondents)
    row.errors.correspondence_per_diagonal = core::correspondence_error(
        core::deform_points(model, result, model.normalization.undo(model.canonical), {},
                            core::Follow::material),
        *truth.correspondents, truth.tested->diagonal);
  if (variant != core::Variant::holistic) row.seam = core::seam_gap(model, result);
  if (model.canonical_mesh.faces.rows() > 0) row.mesh_stretch = result.figures.mesh_stretch;
  row.figures = result.figures;
  row.verdict = result.assessment.verdict;
  row.seconds = result.seconds;
  return row;
}

// A cut that found nothing (no plane, no cluster, too few points to register): its rows carry no error.
eval::EvalRow failed_row() {
  eval::EvalRow row;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  row.errors.eq5 = row.errors.eq5_per_diagonal2 = row.errors.reverse_eq5 = nan;
  row.errors.symmetric_rms_per_diagonal = row.errors.chamfer = row.errors.chamfer_per_diagonal = nan;
  return row;
}

}  // namespace

void check_settings(const DepthSceneSettings& settings) {
  if (settings.scenes < 0) throw UsageError("--scenes must be 0 (none) or more");
  if (!(settings.object_size > 0 && settings.object_size < 10))
    throw UsageError("--scene-size: the held-out object's diagonal on the table is metres in (0, 10)");
  if (settings.neighbours < 0) throw UsageError("the neighbour count of a depth scene must be 0 or more");
  if (settings.elevations_degrees.empty())
    throw UsageError("depth scenes need at least one camera elevation");
  for (double elevation : settings.elevations_degrees)
    if (!(elevation > 0 && elevation <= 90))
      throw UsageError("camera elevations of depth scenes are degrees in (0, 90]");
}

DepthScenes::DepthScenes(DepthSceneSettings settings) : settings_(std::move(settings)) {
  check_settings(settings_);
}

int DepthScenes::jobs(const eval::EvalInput& input, const eval::TestedInstance& tested) const {
  return has_mesh(input.instances[tested.index]) ? settings_.scenes : 0;
}

std::vector<std::size_t> pick_neighbours(const eval::EvalInput& input,
                                         const std::vector<std::size_t>& training, int count,
                                         std::uint64_t seed) {
  std::vector<std::size_t> candidates;
  for (std::size_t i : training)
    if (has_mesh(input.instances[i])) candidates.push_back(i);
  // A seeded Fisher-Yates prefix: std::shuffle's result differs between standard libraries.
  std::mt19937_64 random(seed);
  const std::size_t kept = std::min(candidates.size(), static_cast<std::size_t>(std::max(count, 0)));
  for (std::size_t i = 0; i < kept; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(random() % (candidates.size() - i));
    std::swap(candidates[i], candidates[j]);
  }
  candidates.resize(kept);
  return candidates;
}

namespace {

// One cut of the scene (the scene library's, or the hand cut through the true mask) registered with every
// variant: rows[v] for variant v.
void cut_and_register(eval::CutKind kind, const RenderedScene& scene, const DepthSceneSettings& scenes,
                      const eval::EvalSettings& settings, const core::CategoryModel& model,
                      const CutTruth& truth, const std::vector<core::Variant>& variants,
                      eval::EvalRow* rows) {
  const scene::PixelMask* mask = kind == eval::CutKind::hand ? &scene.mask : nullptr;
  const scene::SceneView view = scene::depth_view(scene.rendered.depth, scenes.intrinsics, mask);
  std::optional<scene::SceneCut> cut;
  try {
    cut = in_units(scene::cut_scene(view, {}, scenes.cut.segmentation), scene.metres_per_unit);
  } catch (const InputError&) {
    // No plane or no cluster: the scene cut chose nothing, which the right-object share counts.
  }
  for (std::size_t v = 0; v < variants.size(); ++v) {
    rows[v] = failed_row();
    if (cut) try {
        rows[v] = registered_row(model, settings, scenes, *cut, variants[v], truth);
      } catch (const InputError&) {
        // Too few points to register: the row keeps no error.
      }
    rows[v].variant = core::enum_name(variants[v]);
    rows[v].observed_points = cut ? static_cast<int>(cut->object.points.rows()) : 0;
    rows[v].scene = cut ? score_cut(kind, cut->object, scene) : eval::SceneCutScore{kind, 0.0, 0.0};
  }
}

}  // namespace

void DepthScenes::run(const eval::EvalInput& input, const eval::EvalSettings& settings,
                      const core::CategoryModel& model, const eval::TestedInstance& tested, int job,
                      const std::vector<core::Variant>& variants, eval::EvalRow* rows) const {
  // Seeds of the scenes stay apart from the point-sampled views' (which mix in view + 1 >= 0).
  const std::uint64_t seed =
      eval::mix_seed(eval::mix_seed(eval::mix_seed(settings.seed, tested.index), 0x5ce9e5ULL), job);
  const Eigen::Vector3d up =
      core::with_model_defaults(settings.registration, model).initialisation.up.value();
  const std::vector<std::size_t> neighbours =
      pick_neighbours(input, tested.training, settings_.neighbours, eval::mix_seed(seed, 1));
  const RenderedScene scene = render_scene(settings_, input, tested.index, neighbours, up, job, seed);
  const core::KdTree truth(eval::moved_by(*tested.truth, scene.T_camera_object));
  const std::optional<core::Points> correspondents =
      tested.correspondents ? std::optional(eval::moved_by(*tested.correspondents, scene.T_camera_object))
                            : std::nullopt;
  const CutTruth cut_truth{&truth, correspondents ? &*correspondents : nullptr, &tested};
  // The scene cut's rows (one per variant), then the hand cut's.
  cut_and_register(eval::CutKind::scene, scene, settings_, settings, model, cut_truth, variants, rows);
  cut_and_register(eval::CutKind::hand, scene, settings_, settings, model, cut_truth, variants,
                   rows + variants.size());
  // The camera's direction from the object's box centre, in the object's frame (as a partial view's).
  const Eigen::Vector3d centre =
      ((tested.truth->colwise().minCoeff() + tested.truth->colwise().maxCoeff()) / 2).transpose();
  const Eigen::Vector3d direction = (scene.T_camera_object.inverse().translation() - centre).normalized();
  for (std::size_t r = 0; r < rows_per_job(variants.size()); ++r) {
    eval::EvalRow& row = rows[r];
    row.category = input.category, row.instance = input.instances[tested.index].name;
    row.canonical = model.training.canonical, row.fold = tested.fold, row.view = job,
    row.direction = direction;
    row.diagonal = tested.diagonal, row.errors.diagonal = tested.diagonal;
  }
}

}  // namespace partreg::scene_eval
