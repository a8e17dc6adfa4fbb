#pragma once
// Folds and spikes out of a deformed mesh. A shape space's field can turn a thin feature inside out (a
// ShapeNet mug's mean shape already turned 718 of 22140 faces over at its handle, where the Jacobian's
// determinant fell to -0.6) and the refinement can pull an edge to several times its length. Where it does,
// the displacement is smoothed, as little as removes the fault, within a bound on how far the surface moves;
// everywhere else the mesh is the field's.

#include <Eigen/Core>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::core::detail {

/// What counts as a fault and how far the repair may spread.
struct MeshFaults {
  double stretch_limit = 3.0;  ///< an edge longer than this many times its reference length is a fault
  int rings = 2;               ///< vertex rings around the faults that are repaired with them
  int rounds = 10;             ///< repairs at most, each over a wider region while faults remain
  /// Each round smooths the displacement with this pull to its own value (screened Laplacian), the first
  /// round's, times screen_step per round: gentle first, the harmonic fill last.
  double first_screen = 1.0, screen_step = 0.25;
  /// A repair moving a vertex farther than this share of the reference's diagonal is not kept (the fit's
  /// surface matters more than the fold; the verdict counts observed points within 0.02 as inliers).
  double largest_shift = 0.05;
};

/// The faces of `deformed` (vertices of `canonical`'s faces, moved) that are turned over against `reference`
/// (the canonical vertices, posed: same orientation, lengths in the deformed units) or have an edge longer than
/// faults.stretch_limit times the reference's.
std::vector<int> faulty_faces(const Faces& faces, const Points& reference, const Points& deformed,
                              const MeshFaults& faults);

/// `deformed` with its faulty faces' neighbourhoods repaired: the displacement from `reference` there is
/// smoothed (cotangent weights, vertices at one position moving as one) with the fixed displacement of the
/// vertices around it as its boundary, as far as the faults need and faults.largest_shift allows.
Points relax_faults(const Faces& faces, const Points& reference, const Points& deformed, const MeshFaults& faults);

}  // namespace partreg::core::detail
