#pragma once
/// \file
/// Turning surfaces into point sets and point sets into smaller ones.

#include <cstdint>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::core {

/// `count` points uniformly distributed over the mesh's area (each triangle drawn with probability
/// proportional to its area, then a uniform point inside it), with the triangle's normal. Deterministic
/// for a seed. Works on open meshes with inner faces (ShapeNet): nothing assumes a closed surface.
/// Throws InputError for a mesh without faces or area, and UsageError for count 0. With `face_of_point`, also
/// the face each point was drawn from (a part per face gives the sample its parts).
Cloud sample_surface(const Mesh& mesh, std::size_t count, std::uint64_t seed,
                     Eigen::VectorXi* face_of_point = nullptr);

/// Farthest-point downsampling: `count` row indices, starting at row `first`, each next point the one
/// farthest from those already chosen. Chosen over a voxel grid because it keeps thin parts (handles,
/// spouts, triggers) covered whatever their size, and returns exactly `count` points. Each pick updates only
/// the points within reach of it (a KD-tree query), so it costs far less than O(N count) on a surface; ties go
/// to the lowest row. Throws InputError when the set has fewer than `count` points or a non-finite point.
std::vector<int> farthest_point_indices(const Points& points, std::size_t count, int first = 0);

/// One point per occupied voxel of edge `voxel_size` (the point nearest to the voxel's centroid, so every
/// kept point is a real measurement), as row indices in the input's order. O(N). Throws UsageError for a
/// size that is not positive.
std::vector<int> voxel_representatives(const Points& points, double voxel_size);

/// At most `count` rows spread over the set: a voxel pre-pass of `voxel_size` (0 = none), then
/// farthest-point sampling of the voxels' representatives. The pre-pass makes a huge cloud (a depth camera's
/// million points) cost O(N) plus FPS over the voxels; a voxel well under the kept points' spacing leaves
/// the farthest-point choice almost as it was. Every row when the set has no more than `count`; the voxels'
/// representatives when they are fewer than `count`.
std::vector<int> subsample_indices(const Points& points, std::size_t count, double voxel_size);

/// The rows of `points` that have company, in the input's order: a row whose `neighbours`-th nearest other
/// row is farther than `limit` times the median of that distance over the set stands alone (a stray return,
/// dust before the sensor, a uniform outlier; but also a surface seen thinly, as a handle edge-on). With
/// registration's 2 neighbours and limit 3, a half of a sphere sampled three times more thinly than the
/// other keeps every point (four times: 99.6%) and 2 of 364 uniform outliers off it have company
/// (tests/core/sampling_test.cpp). Every row when `limit` is 0, the set has no more than `neighbours` + 1
/// rows or most rows repeat (a median of 0).
std::vector<int> rows_with_neighbours(const Points& points, int neighbours, double limit);

/// The rows labelled `part` (part index per row in `part_of_row`), in order.
std::vector<int> rows_with(const Eigen::VectorXi& part_of_row, int part);

/// The rows of `points` listed in `rows`, in that order.
Points select_rows(const Points& points, const std::vector<int>& rows);

}  // namespace partreg::core
