#pragma once
/// \file
/// The evaluation's depth scenes: each held-out instance stands on a table between two training instances,
/// seen by the structured-light camera of depth_render.hpp, and is cut out and registered as `register
/// --depth` does (cut_scene's plane removal, clusters and pick nearest the image centre, then register_cut).
/// The same depth image is also cut by hand (the instance's own measured pixels, its true mask) and
/// registered the same way, so the cost of the scene cut shows as a ratio.
///
/// This lives in its own library above both eval and scene: eval links the core only (scene would bring
/// PCL and the io layer into every evaluation build), scene links the core and io, and neither may depend
/// on the other's results. It plugs into run_evaluation through eval::ExtraObservations.

#include <cstdint>
#include <vector>

#include "partreg/eval/protocol.hpp"
#include "partreg/scene/camera.hpp"
#include "partreg/scene/depth_render.hpp"
#include "partreg/scene/scene_options.hpp"
#include "partreg/scene/table_scene.hpp"

namespace partreg::scene_eval {

/// What the depth scenes are.
struct DepthSceneSettings {
  int scenes = 0;  ///< depth scenes per held-out instance (0 = none)
  /// The held-out instance's bounding-box diagonal on the table (m); its neighbours get the same metres per
  /// data unit, so the category's sizes keep their ratios. A mug is about 0.15 m across its diagonal.
  double object_size = 0.15;
  int neighbours = 2;  ///< training instances standing beside it (fewer when the fold has fewer)
  /// Camera elevations above the table (degrees), used in turn by the scenes: each scene also turns every
  /// object by its own seeded yaw, so the held-out instance is seen from all round.
  std::vector<double> elevations_degrees = {45.0, 30.0, 60.0};
  scene::TableLayout layout;     ///< distance and spacing (m); the elevation and seed are the scene's
  scene::Intrinsics intrinsics;  ///< `partreg scene`'s camera: 640x480, fx = fy = 615
  scene::SensorSettings sensor;  ///< noise, quantisation, lost pixels; the seed is the scene's
  scene::SceneSettings cut;      ///< the cut and its registration, as `register --depth` takes them
};

/// UsageError (one line) for settings out of range: a negative scene count, a size outside (0, 10) m, no
/// elevation or one outside (0, 90] degrees, a negative neighbour count.
void check_settings(const DepthSceneSettings& settings);

/// The depth scenes as eval::ExtraObservations. Each scene gives the scene cut's rows (one per variant), then
/// the hand cut's, with EvalRow::scene set. Instances without a mesh get no scenes (nothing to render).
class DepthScenes : public eval::ExtraObservations {
 public:
  explicit DepthScenes(DepthSceneSettings settings);
  int jobs(const eval::EvalInput& input, const eval::TestedInstance& tested) const override;
  std::size_t rows_per_job(std::size_t variants) const override { return 2 * variants; }
  void run(const eval::EvalInput& input, const eval::EvalSettings& settings, const core::CategoryModel& model,
           const eval::TestedInstance& tested, int job, const std::vector<core::Variant>& variants,
           eval::EvalRow* rows) const override;

 private:
  DepthSceneSettings settings_;
};

/// Which training instances stand beside the held-out one in a scene: `count` distinct ones (all of them when
/// there are fewer) drawn by `seed` from `training`, skipping any without a mesh.
std::vector<std::size_t> pick_neighbours(const eval::EvalInput& input,
                                         const std::vector<std::size_t>& training, int count,
                                         std::uint64_t seed);

}  // namespace partreg::scene_eval
