#pragma once
/// \file
/// The scripted GUI sessions the render and window tests replay (and docs/gui.md shows), on the synthetic
/// fixtures of ui_fixtures.hpp.

#include <string>

#include "ui/ui_fixtures.hpp"

namespace partreg::testing {

/// Labelling a synthetic mug's handle by painting, then filling the rest as the body.
inline std::string label_script() {
  return "load " + mug_mesh_path().string() +
         "\ncamera side\ncreate_part handle\npaint 860 300 radius=25\npaint 870 380 radius=25\n"
         "paint 860 460 radius=25\nfill 815 330\ncreate_part body\nfill 700 420\n";
}

/// The holistic space's first direction at +2 standard deviations.
inline std::string shape_script() {
  return "load " + small_model_path().string() + "\nset_latent holistic 1 2.0\ncamera iso\n";
}

/// A hol+part registration stepped back to its 10th step.
inline std::string registration_script() {
  return "load " + small_model_path().string() + "\nload " + observed_cloud_path().string() +
         "\nregister hol+part\ngoto_step 10\ncamera front\n";
}

}  // namespace partreg::testing
