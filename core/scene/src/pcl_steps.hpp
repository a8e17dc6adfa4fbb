#pragma once
// The steps of the scene cut that PCL does (internal to partreg_scene). Only pcl_steps.cpp includes PCL's
// headers: they are slow to compile, and their flags break other translation units.

#include <Eigen/Core>
#include <vector>

#include "partreg/core/types.hpp"
#include "partreg/scene/segmentation.hpp"

namespace partreg::scene::detail {

/// One point per occupied voxel of `leaf` (m), the centroid of its points; the points as they are for 0.
core::Points voxelised(const core::Points& points, double leaf);

/// Rows of `points` kept by PCL's statistical outlier removal (settings' neighbours and deviations).
std::vector<int> inlier_rows(const core::Points& points, const SegmentationSettings& settings);

/// RANSAC's best plane (n, d with |n| = 1) and its inlier rows; an empty inlier list when none was found.
struct PlaneFit {
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();
  std::vector<int> inliers;
};
PlaneFit fit_plane(const core::Points& points, const SegmentationSettings& settings);

/// Euclidean clusters of the rows `rows` of `points`, each a list of rows, largest first.
std::vector<std::vector<int>> euclidean_clusters(const core::Points& points, const std::vector<int>& rows,
                                                 const SegmentationSettings& settings);

}  // namespace partreg::scene::detail
