#pragma once
/// \file
/// A scene as an observation: the flags that give a depth image with its camera (--depth, --intrinsics,
/// --mask) or a scene cloud (--scene), the object's pick, and the cut's settings; `segment` and `register`
/// share them. The object is cut out (scene/segmentation.hpp) and registered in the camera frame with the
/// camera's origin as the viewpoint (scene/scene_registration.hpp).

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "partreg/core/registration/registration.hpp"
#include "partreg/scene/scene_options.hpp"
#include "partreg/scene/segmentation.hpp"

namespace partreg::app {

struct ObservationInput {
  std::string depth, intrinsics, mask, scene, pick;
  scene::SceneSettings settings;

  /// True when a depth image or a scene cloud was given.
  bool is_scene() const { return !depth.empty() || !scene.empty(); }
  /// The file the scene came from (the depth image or the scene cloud).
  const std::string& source() const { return depth.empty() ? scene : depth; }
};

/// Adds --depth, --intrinsics, --mask, --scene (unless `with_scene_flag` is false: `segment` takes the scene
/// cloud as its argument), --pick and the scene options.
void add_observation_flags(CLI::App* command, ObservationInput& input, bool with_scene_flag = true);

/// "U,V" (a pixel) or "X,Y,Z" (a camera-frame point, m); UsageError otherwise.
scene::Pick parse_pick(const std::string& text);

/// Reads the scene the flags name and cuts the object out, logging the plane, the clusters and the choice.
/// UsageError for a contradictory set of flags.
scene::SceneCut cut_observation(const ObservationInput& input);

/// The cut for a result file: the plane, the up axis, the clusters and the choice.
nlohmann::json cut_json(const scene::SceneCut& cut);

/// What `register` fits: OBSERVED read as it is, or the object cut out of the scene the flags name.
struct Observed {
  core::Points points;
  std::optional<scene::SceneCut> cut;
};

/// Reads `observed_path` (a cloud or a mesh sampled to `mesh_samples`) or cuts the scene; UsageError unless
/// exactly one of them is given, or for --viewpoint with a scene (its viewpoint is the camera).
Observed read_observed(const std::string& observed_path, const ObservationInput& input,
                       const core::RegistrationSettings& settings, std::size_t mesh_samples);

/// Registers: register_observation, or for a cut scene register_cut (about the table's normal, from the
/// camera), logging the angle between the registered up axis and the table's normal.
core::RegistrationResult register_observed(const core::CategoryModel& model, const Observed& observed,
                                           const core::RegistrationSettings& settings,
                                           const ObservationInput& input, const core::ProgressListener& progress);

}  // namespace partreg::app
