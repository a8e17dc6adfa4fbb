#pragma once
/// \file
/// Test scenes: objects standing on a table, seen from above at an angle by a depth camera (depth_render.hpp).
/// The world frame has z up with the table top at z = 0; object 0 stands at the world origin, the others in
/// turn to its left and right; each is turned about the up axis by a seeded random yaw.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::scene {

/// An object to place, in its own frame and units.
struct TableObject {
  core::Mesh mesh;
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();  ///< its up axis in its own frame (ShapeNet's: +y)
  double size = 0.15;  ///< its bounding-box diagonal on the table (m): it is scaled to it
};

/// Where things go.
struct TableLayout {
  double distance = 0.6;            ///< camera to object 0's foot (m)
  double elevation_degrees = 45.0;  ///< camera above the table plane (degrees)
  double spacing = 0.2;             ///< between neighbouring objects' centres (m)
  double table_width = 1.2, table_depth = 1.0;  ///< the table top (m)
  std::uint64_t seed = 1;           ///< the objects' yaws
};

/// One placed object.
struct PlacedObject {
  core::Mesh mesh;  ///< in the camera frame (m)
  /// Object frame (its own units) -> camera frame (m): a rotation times `scale`, then a translation.
  Eigen::Matrix4d T_camera_object = Eigen::Matrix4d::Identity();
  double scale = 1.0;  ///< metres per unit of the object's own frame
};

struct TableScene {
  std::vector<PlacedObject> objects;
  core::Mesh table;  ///< the table top in the camera frame
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();  ///< the table top, n . x + d = 0, n towards the camera
  Eigen::Matrix4d T_world_camera = Eigen::Matrix4d::Identity();
};

/// Lays `objects` out on a table. InputError for an empty mesh; UsageError for a layout out of range.
TableScene lay_out_table(const std::vector<TableObject>& objects, const TableLayout& layout = {});

}  // namespace partreg::scene
