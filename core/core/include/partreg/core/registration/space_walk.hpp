#pragma once
/// \file
/// Walking the shape spaces: points deformed by chosen latents with every pose the identity (the app's
/// sliders, `figure space`), and the stretch figure that says whether a walk tears the canonical mesh.
/// Eq. 4 as deform_points applies it, with the same seam blending; all in normalised units.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/space/category_model.hpp"

namespace partreg::core {

/// Points moved by the holistic space alone, or by every part's space blended at the seams. The blend
/// weights and G(z, C_s) times each space's mean and basis fields are computed once, so a deformation
/// costs one small product per point and space (no kernel evaluations).
class SpaceWalk {
 public:
  /// `normalised`: the points to move (normalised units). `holistic`: the holistic space moves them, else
  /// the part spaces (UsageError for a model without parts).
  SpaceWalk(const CategoryModel& model, const Points& normalised, bool holistic, const SeamBlend& blend = {});

  /// The points moved by the spaces at `latents` (one per model space, model.spaces order; spaces that do
  /// not take part are ignored), normalised units. UsageError for a latent of the wrong length.
  Points deform(const std::vector<Eigen::VectorXd>& latents) const;

 private:
  struct Term {
    int space = 0;               ///< index into model.spaces
    std::vector<int> rows;       ///< points this space moves (blend weight above zero)
    Eigen::VectorXd weight;      ///< its blend weight at those points
    Eigen::MatrixXd mean;        ///< rows x 3: G(z, C) W_mean, weighted
    Eigen::MatrixXd per_latent;  ///< (rows * 3) x q: G(z, C) basis_k, weighted, row-major per point
  };
  Points points_;
  std::vector<Term> terms_;
};

/// Largest ratio of an edge's deformed length to its canonical length over the mesh's edges (edges
/// shorter than 1e-9 in the canonical are skipped). `deformed` holds the mesh's vertices moved.
double max_edge_stretch(const Mesh& canonical, const Points& deformed);

/// The stretch figure of one space's walk: the largest edge stretch over the grid.
struct SpaceStretch {
  std::string space;
  double max_stretch = 0.0;  ///< deformed / canonical edge length, largest over the grid
  int direction = 0;         ///< principal direction (0-based) where it is reached
  double std_devs = 0.0;     ///< standard deviations along it where it is reached
};

/// Every space's walk over its grid: each principal direction at each of `std_devs` standard deviations
/// (the others at zero), the canonical mesh deformed by that space (with the other parts at their means
/// when it is a part). Needs a canonical mesh (InputError otherwise).
std::vector<SpaceStretch> space_grid_stretch(const CategoryModel& model,
                                             const std::vector<double>& std_devs = {-2.0, -1.0, 0.0, 1.0,
                                                                                    2.0},
                                             const SeamBlend& blend = {});

}  // namespace partreg::core
