#pragma once
/// \file
/// The point and mesh types shared by every partreg library.
///
/// Convention for the whole project: a set of points is an N x 3 matrix, one point per row, stored
/// row-major so that each point's coordinates are contiguous (KD-trees and the CPD E-step walk points
/// one at a time). Deformation weights W (M x 3) follow the same layout, so T = C + G W reads as in
/// the paper.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace partreg::core {

/// N points, one per row (x, y, z), in whatever frame the variable's name states.
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Triangles as three vertex indices per row (counter-clockwise seen from outside, where that is known).
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// A triangle mesh. Normals are optional (empty or one per vertex).
struct Mesh {
  Points vertices;
  Faces faces;
  Points normals;  ///< empty, or one unit normal per vertex
};

/// A point cloud with optional per-point normals.
struct Cloud {
  Points points;
  Points normals;  ///< empty, or one unit normal per point
};

}  // namespace partreg::core
