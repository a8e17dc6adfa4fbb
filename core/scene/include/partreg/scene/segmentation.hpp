#pragma once
/// \file
/// Cutting an object out of a scene seen by a depth camera, with PCL: the support plane found by RANSAC
/// (SACSegmentation) and removed, statistical outliers removed, the rest split into Euclidean clusters, and
/// one cluster chosen: the one at a picked pixel or point, or else the one nearest the image centre (the
/// optical axis) above the plane. The plane's normal, turned towards the camera, is the scene's up axis.
/// Lengths are in metres (the camera frame's units).

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/geometry/free_space.hpp"
#include "partreg/scene/camera.hpp"

namespace partreg::scene {

/// How a scene is cut. Defaults suit a table-top seen from 0.4 to 1.5 m by an RGB-D camera.
struct SegmentationSettings {
  double voxel_size = 0.004;      ///< the plane and clusters are found on a voxel grid this fine (m; 0 = none)
  double plane_distance = 0.01;   ///< RANSAC inlier distance to the plane (m)
  int plane_iterations = 1000;    ///< RANSAC iterations
  double min_plane_share = 0.1;   ///< a plane needs at least this share of the measured points
  int outlier_neighbours = 20;    ///< statistical outlier removal: neighbours whose mean distance is judged
  double outlier_deviations = 2.0;  ///< ... and removed beyond this many standard deviations of that mean
  double cluster_tolerance = 0.04;  ///< Euclidean clustering: points closer than this join (m)
  int min_cluster_points = 50;      ///< smaller clusters (voxelised points) are noise
};

/// Which cluster is the object.
struct Pick {
  std::optional<Eigen::Vector2d> pixel;  ///< (u, v): the cluster at this pixel
  std::optional<Eigen::Vector3d> point;  ///< (x, y, z) camera frame (m): the cluster nearest this point
};

/// A scene as the camera saw it: its points in the camera frame (m), each with its pixel where known.
struct SceneView {
  CameraPoints measured;
  std::optional<Intrinsics> intrinsics;  ///< known for a depth image, or given with a scene cloud
  std::optional<PixelMask> mask;         ///< the object's pixels, when given: the object is these pixels
};

/// One cluster found above the plane.
struct Cluster {
  int points = 0;                 ///< voxelised points
  Eigen::Vector3d centroid;       ///< camera frame (m)
  double off_axis_degrees = 0.0;  ///< angle between the centroid's ray and the optical axis
};

/// What the cut found and chose.
struct SceneCut {
  CameraPoints object;      ///< the chosen object's points at full resolution (camera frame, m)
  core::Points plane_points;  ///< the plane's inliers (voxelised, camera frame, m)
  /// n . x + d = 0 with n (unit) pointing to the camera's side: (n_x, n_y, n_z, d).
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();
  Eigen::Vector3d up = Eigen::Vector3d::Zero();  ///< the plane's normal, towards the camera (camera frame)
  std::vector<Cluster> clusters;                  ///< largest first
  int chosen = -1;                                ///< index into clusters (-1: the mask chose the object)
  std::string choice;                             ///< how the object was chosen, for people
  int outliers_removed = 0;                       ///< voxelised points removed as statistical outliers
  /// The space the camera saw empty (camera frame, m): from the whole view, so the table and the background
  /// count as well as the object; empty without intrinsics (free_space_of).
  std::shared_ptr<const core::FreeSpace> free_space;
};

/// The view's free space: every measured point's depth at its pixel (the nearest where several share one:
/// a scene cloud projected), 0 elsewhere, with the sensor noise's defaults (core::FreeSpace). Empty without
/// intrinsics.
std::shared_ptr<const core::FreeSpace> free_space_of(const SceneView& view);

/// Cuts the object out of `view`. UsageError for a pixel pick outside the image or without intrinsics;
/// InputError for too few points, no plane, no cluster, or a pick that hits no cluster.
SceneCut cut_scene(const SceneView& view, const Pick& pick = {}, const SegmentationSettings& settings = {});

}  // namespace partreg::scene
