#pragma once
/// \file
/// The settings of a scene's cut and of its registration as named options (core/options/setting_option.hpp):
/// the `segment` and `register` commands take them as --NAME, the Python module as keywords (- as _).

#include <vector>

#include "partreg/core/options/setting_option.hpp"
#include "partreg/scene/scene_registration.hpp"
#include "partreg/scene/segmentation.hpp"

namespace partreg::scene {

/// Everything a scene adds to a request.
struct SceneSettings {
  SegmentationSettings segmentation;
  SceneRegistrationSettings registration;
};

using SceneOption = core::SettingOption<SceneSettings>;

/// The table: scene-voxel, plane-distance, plane-iterations, min-plane-share, outlier-neighbours,
/// outlier-deviations, cluster-tolerance, min-cluster-points, search-tilts.
const std::vector<SceneOption>& scene_options();

}  // namespace partreg::scene
