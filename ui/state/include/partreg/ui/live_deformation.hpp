#pragma once
/// \file
/// The canonical mesh deformed live by a shape space (paper Eq. 4): v(z) = G(z, C) W(x) with
/// W(x) = mean + basis x. G(V, C) times the mean and each basis field is computed once per space, so a
/// slider move costs one small matrix product per vertex (no kernel evaluations).

#include <Eigen/Core>
#include <map>
#include <vector>

#include "partreg/core/category_model.hpp"

namespace partreg::ui {

/// Per space: the displacement of its mesh vertices for the mean and for each unit latent.
class LiveDeformation {
 public:
  LiveDeformation() = default;
  /// Remembers the model; nothing is computed until a space is first used.
  explicit LiveDeformation(const core::CategoryModel* model);

  /// The canonical mesh's vertices (normalised units) deformed by the holistic space at `latents[0]`
  /// when `holistic` is true, else each part's vertices by its own space at `latents[1 + part]`.
  /// `latents[s]` holds space s's latent (its length is that space's dimensions).
  core::Points deform(const std::vector<Eigen::VectorXd>& latents, bool holistic);

  /// Training instance `instance`'s holistic fit, exactly as CPD left it: the canonical mesh's vertices
  /// moved by G(V, C) W_i, or without a mesh the canonical points moved by G(C, C) W_i (normalised units).
  /// Computed once per instance (one kernel pass), then kept.
  const core::Points& fitted_instance(int instance);

 private:
  struct SpaceCache {
    bool ready = false;
    std::vector<int> vertices;   ///< mesh vertices this space moves
    Eigen::MatrixXd mean;        ///< vertices x 3
    Eigen::MatrixXd per_latent;  ///< (vertices * 3) x q, row-major per vertex
  };
  void prepare(int space);
  const core::CategoryModel* model_ = nullptr;
  std::vector<SpaceCache> caches_;
  std::map<int, core::Points> instances_;
};

}  // namespace partreg::ui
