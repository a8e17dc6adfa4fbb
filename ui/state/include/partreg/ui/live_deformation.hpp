#pragma once
/// \file
/// The canonical mesh deformed live by the shape spaces (paper Eq. 4, core::SpaceWalk: parts blended at
/// their seams exactly as `figure space` and registration results are). Each walk is prepared once, so a
/// slider move costs one small matrix product per vertex (no kernel evaluations).

#include <Eigen/Core>
#include <map>
#include <optional>
#include <vector>

#include "partreg/core/registration/space_walk.hpp"
#include "partreg/core/space/category_model.hpp"

namespace partreg::ui {

/// The holistic walk and the parts' walk of the canonical mesh, each prepared when first used.
class LiveDeformation {
 public:
  LiveDeformation() = default;
  /// Remembers the model; nothing is computed until a space is first used.
  explicit LiveDeformation(const core::CategoryModel* model);

  /// The canonical mesh's vertices (normalised units) deformed by the holistic space at `latents[0]`
  /// when `holistic` is true, else by every part's space at `latents[1 + part]`, blended at the seams.
  /// `latents[s]` holds space s's latent (its length is that space's dimensions).
  core::Points deform(const std::vector<Eigen::VectorXd>& latents, bool holistic);

  /// Training instance `instance`'s holistic fit, exactly as CPD left it: the canonical mesh's vertices
  /// moved by G(V, C) W_i, or without a mesh the canonical points moved by G(C, C) W_i (normalised units).
  /// Computed once per instance (one kernel pass), then kept.
  const core::Points& fitted_instance(int instance);

 private:
  const core::CategoryModel* model_ = nullptr;
  std::optional<core::SpaceWalk> holistic_, parts_;
  std::map<int, core::Points> instances_;
};

}  // namespace partreg::ui
