#include "partreg/scene/table_scene.hpp"

#include <cmath>
#include <random>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/normalization.hpp"

namespace partreg::scene {
namespace {

core::Mesh transformed(const core::Mesh& mesh, const Eigen::Matrix4d& T) {
  core::Mesh out = mesh;
  const Eigen::Matrix3d A = T.topLeftCorner<3, 3>();
  out.vertices = (mesh.vertices * A.transpose()).rowwise() + T.topRightCorner<3, 1>().transpose();
  if (out.normals.rows() > 0) out.normals = (mesh.normals * A.transpose()).rowwise().normalized();
  return out;
}

// The camera on the table's -y side, looking at the world origin, x to the right of the image, y down it.
Eigen::Matrix4d camera_pose(const TableLayout& layout) {
  const double e = layout.elevation_degrees * M_PI / 180.0;
  const Eigen::Vector3d centre = layout.distance * Eigen::Vector3d(0, -std::cos(e), std::sin(e));
  const Eigen::Vector3d forward = -centre.normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 1>(0, 0) = right, T.block<3, 1>(0, 1) = down, T.block<3, 1>(0, 2) = forward;
  T.block<3, 1>(0, 3) = centre;
  return T;
}

// Object frame -> world: up to +z, a yaw, scaled to its size, its foot centred on `slot` at z = 0.
Eigen::Matrix4d world_pose(const TableObject& object, double yaw, const Eigen::Vector2d& slot, double& scale) {
  scale = object.size / core::bounding_box_diagonal(object.mesh.vertices);
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                             Eigen::Quaterniond::FromTwoVectors(object.up.normalized(), Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  const core::Points turned = scale * object.mesh.vertices * R.transpose();
  const Eigen::Vector3d low = turned.colwise().minCoeff(), high = turned.colwise().maxCoeff();
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = scale * R;
  T.topRightCorner<3, 1>() = Eigen::Vector3d(slot.x() - (low.x() + high.x()) / 2, slot.y() - (low.y() + high.y()) / 2, -low.z());
  return T;
}

core::Mesh table_top(const TableLayout& layout) {
  core::Mesh table;
  const double w = layout.table_width / 2, d = layout.table_depth / 2;
  table.vertices.resize(4, 3);
  table.vertices << -w, -d, 0, w, -d, 0, w, d, 0, -w, d, 0;
  table.faces.resize(2, 3);
  table.faces << 0, 1, 2, 0, 2, 3;
  return table;
}

}  // namespace

TableScene lay_out_table(const std::vector<TableObject>& objects, const TableLayout& layout) {
  if (!(layout.distance > 0 && layout.elevation_degrees > 0 && layout.elevation_degrees <= 90 &&
        layout.spacing >= 0 && layout.table_width > 0 && layout.table_depth > 0))
    throw UsageError("table layout out of range (distance > 0, elevation in (0, 90] degrees, spacing >= 0)");
  TableScene scene;
  scene.T_world_camera = camera_pose(layout);
  const Eigen::Matrix4d T_camera_world = scene.T_world_camera.inverse();
  std::mt19937_64 random(layout.seed);
  std::uniform_real_distribution<double> yaw(0.0, 2.0 * M_PI);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].mesh.vertices.rows() == 0 || objects[i].mesh.faces.rows() == 0)
      throw InputError("object " + std::to_string(i) + " has no mesh");
    if (!(objects[i].size > 0)) throw UsageError("object sizes must be positive");
    const double side = (i % 2 ? -1.0 : 1.0) * layout.spacing * double((i + 1) / 2);
    PlacedObject placed;
    placed.T_camera_object = T_camera_world * world_pose(objects[i], yaw(random), {side, 0.0}, placed.scale);
    placed.mesh = transformed(objects[i].mesh, placed.T_camera_object);
    scene.objects.push_back(std::move(placed));
  }
  scene.table = transformed(table_top(layout), T_camera_world);
  const Eigen::Vector3d normal = T_camera_world.topLeftCorner<3, 3>() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d on_plane = T_camera_world.topRightCorner<3, 1>();  // the world origin
  scene.plane << normal, -normal.dot(on_plane);
  return scene;
}

}  // namespace partreg::scene
