// Folds and spikes out of a deformed mesh (core/core/src/geometry/mesh_relaxation.hpp): a flat grid folded
// over in a patch, and one vertex pulled far out of it, are repaired there and left as they were elsewhere.
#include "geometry/mesh_relaxation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace partreg::core::detail {
namespace {

constexpr int kSide = 31;  // vertices per side of the unit grid

Mesh grid() {
  Mesh mesh;
  mesh.vertices.resize(kSide * kSide, 3);
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j)
      mesh.vertices.row(i * kSide + j) << i / (kSide - 1.0), j / (kSide - 1.0), 0.0;
  mesh.faces.resize(2 * (kSide - 1) * (kSide - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < kSide; ++i)
    for (int j = 0; j + 1 < kSide; ++j) {
      const int a = i * kSide + j, b = a + kSide;
      mesh.faces.row(f++) << a, b, a + 1;
      mesh.faces.row(f++) << b, b + 1, a + 1;
    }
  return mesh;
}

// x moved back on itself around x = 0.5 (dx'/dx = 1 - 3 at the centre) inside a window of y around 0.5.
Points folded(const Points& flat) {
  Points moved = flat;
  for (Eigen::Index v = 0; v < flat.rows(); ++v) {
    const double x = flat(v, 0) - 0.5, y = flat(v, 1) - 0.5;
    moved(v, 0) -= 3.0 * x * std::exp(-x * x / (2 * 0.06 * 0.06)) * std::exp(-y * y / (2 * 0.08 * 0.08));
  }
  return moved;
}

double largest_stretch(const Mesh& mesh, const Points& moved) {
  double largest = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int a = mesh.faces(f, e), b = mesh.faces(f, (e + 1) % 3);
      largest = std::max(largest, (moved.row(a) - moved.row(b)).norm() /
                                      (mesh.vertices.row(a) - mesh.vertices.row(b)).norm());
    }
  return largest;
}

// Vertices farther than `radius` from the grid's centre that moved at all in the repair.
int moved_far_away(const Points& flat, const Points& before, const Points& after, double radius) {
  int count = 0;
  for (Eigen::Index v = 0; v < flat.rows(); ++v)
    if ((flat.row(v) - Eigen::RowVector3d(0.5, 0.5, 0.0)).norm() > radius && before.row(v) != after.row(v)) ++count;
  return count;
}

// The grid's folds and spikes are larger than a fitted surface may move (largest_shift): these repairs may
// move it as far as they need.
MeshFaults unbounded() {
  MeshFaults faults;
  faults.largest_shift = 1.0;
  return faults;
}

TEST(MeshRelaxation, AFoldIsUnfoldedWhereItIsAndNowhereElse) {
  const Mesh mesh = grid();
  const Points fold = folded(mesh.vertices);
  const MeshFaults faults = unbounded();
  ASSERT_GT(faulty_faces(mesh.faces, mesh.vertices, fold, faults).size(), 20u);  // the fold turns faces over
  const Points repaired = relax_faults(mesh.faces, mesh.vertices, fold, faults);
  EXPECT_TRUE(faulty_faces(mesh.faces, mesh.vertices, repaired, faults).empty());
  EXPECT_EQ(moved_far_away(mesh.vertices, fold, repaired, 0.4), 0);
  // Repaired, not flattened back to the canonical: the patch's rim keeps the fold's displacement.
  EXPECT_GT((repaired - mesh.vertices).rowwise().norm().maxCoeff(), 0.02);
}

TEST(MeshRelaxation, ASpikeIsBroughtWithinTheStretchLimit) {
  const Mesh mesh = grid();
  Points spiked = mesh.vertices;
  const int centre = (kSide / 2) * kSide + kSide / 2;
  spiked(centre, 2) = 0.3;  // nine edge lengths out of the plane
  const MeshFaults faults = unbounded();
  ASSERT_GT(largest_stretch(mesh, spiked), 8.0);
  const Points repaired = relax_faults(mesh.faces, mesh.vertices, spiked, faults);
  EXPECT_LE(largest_stretch(mesh, repaired), faults.stretch_limit);
  EXPECT_EQ(moved_far_away(mesh.vertices, spiked, repaired, 0.3), 0);
}

TEST(MeshRelaxation, SplitVerticesMoveAsOneAndASoundMeshIsLeftAlone) {
  Mesh mesh = grid();
  // The faces right of x = 0.5 use copies of the seam's vertices, as a mesh file split at a seam holds them.
  const Eigen::Index originals = mesh.vertices.rows();
  mesh.vertices.conservativeResize(originals + kSide, 3);
  const int seam = kSide / 2;
  for (int j = 0; j < kSide; ++j) mesh.vertices.row(originals + j) = mesh.vertices.row(seam * kSide + j);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int e = 0; e < 3; ++e)
      if (mesh.faces(f, e) / kSide == seam && mesh.faces.row(f).maxCoeff() / kSide > seam)
        mesh.faces(f, e) = static_cast<int>(originals) + mesh.faces(f, e) % kSide;
  const MeshFaults faults = unbounded();
  const Points sound = mesh.vertices * 1.5;
  EXPECT_EQ(relax_faults(mesh.faces, mesh.vertices, sound, faults), sound);
  const Points repaired = relax_faults(mesh.faces, mesh.vertices, folded(mesh.vertices), faults);
  EXPECT_TRUE(faulty_faces(mesh.faces, mesh.vertices, repaired, faults).empty());
  for (int j = 0; j < kSide; ++j)
    EXPECT_EQ(repaired.row(originals + j), repaired.row(seam * kSide + j)) << "seam vertex " << j;
}

TEST(MeshRelaxation, AFoldThatOnlyALargeMoveWouldRepairIsLeftAsTheFieldMadeIt) {
  const Mesh mesh = grid();
  const Points fold = folded(mesh.vertices);
  MeshFaults faults;
  faults.largest_shift = 0.005;  // of the grid's diagonal: less than the fold's own depth
  EXPECT_EQ(relax_faults(mesh.faces, mesh.vertices, fold, faults), fold);
}

}  // namespace
}  // namespace partreg::core::detail
