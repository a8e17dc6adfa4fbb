// Grasps carried through a registration (grasp.hpp): contacts as material points, axes with their region.
#include "partreg/core/transfer/grasp.hpp"

#include <cmath>

#include "partreg/core/errors.hpp"
#include "partreg/core/registration/deformation.hpp"

namespace partreg::core {

void validate(const Gripper& gripper) {
  const auto positive = [](double value, const char* name) {
    if (!std::isfinite(value) || !(value > 0.0))
      throw UsageError(std::string("the gripper's ") + name + " must be a positive finite length");
  };
  positive(gripper.max_aperture, "max_aperture");
  positive(gripper.pad_size, "pad_size");
  positive(gripper.finger_depth, "finger_depth");
  if (!std::isfinite(gripper.friction) || gripper.friction < 0.0)
    throw UsageError("the gripper's friction must be a finite number >= 0");
}

Gripper Gripper::in_units(double diagonal) const {
  if (!relative) return *this;
  if (!std::isfinite(diagonal) || !(diagonal > 0.0)) throw InputError("a relative gripper needs an object of some size");
  Gripper absolute = *this;
  absolute.max_aperture *= diagonal, absolute.pad_size *= diagonal, absolute.finger_depth *= diagonal;
  absolute.relative = false;
  return absolute;
}

Eigen::Matrix3d grasp_axes(const Eigen::Vector3d& closing, const Eigen::Vector3d& approach) {
  const Eigen::Vector3d x = closing.normalized();
  Eigen::Vector3d z = approach - approach.dot(x) * x;
  if (z.norm() < 1e-9 * std::max(1.0, approach.norm())) z = x.unitOrthogonal();
  z.normalize();
  Eigen::Matrix3d axes;
  axes.col(0) = x;
  axes.col(1) = z.cross(x);
  axes.col(2) = z;
  return axes;
}

double grasp_region_radius(const CategoryModel& model, const Gripper& gripper) {
  return std::max(kFrameRegionRadius, 2.0 * gripper.pad_size / model.observed_diagonal());
}

std::vector<Grasp> transfer_grasps(const CategoryModel& model, const RegistrationResult& result,
                                   const std::vector<Grasp>& grasps, const Gripper& gripper) {
  validate(gripper);
  const double radius = grasp_region_radius(model, gripper);
  if (grasps.empty()) return {};
  Points contacts(2 * static_cast<Eigen::Index>(grasps.size()), 3);
  std::vector<Points> regions;
  for (std::size_t g = 0; g < grasps.size(); ++g) {
    const auto row = 2 * static_cast<Eigen::Index>(g);
    contacts.row(row) = grasps[g].contact(0).transpose();
    contacts.row(row + 1) = grasps[g].contact(1).transpose();
    regions.push_back(contacts.middleRows(row, 2));
  }
  const Points carried = deform_points(model, result, contacts, {}, Follow::material);
  const std::vector<Eigen::Matrix3d> turns = region_rotations(model, result, regions, radius);
  std::vector<Grasp> moved = grasps;
  for (std::size_t g = 0; g < grasps.size(); ++g) {
    const auto row = 2 * static_cast<Eigen::Index>(g);
    Grasp& out = moved[g];
    // The axes turn with the region: the two contacts' own displacements differ by about the registration's
    // error, which across a wall a few percent of the diagonal thick turned the line joining them by tens of
    // degrees (a mug's carried grasps held 4 of 30 with that line as the closing axis, 19 with the pose alone).
    const Eigen::Vector3d span = (carried.row(row + 1) - carried.row(row)).transpose();
    out.position = 0.5 * (carried.row(row) + carried.row(row + 1)).transpose();
    out.rotation = grasp_axes(turns[g] * grasps[g].closing_axis(), turns[g] * grasps[g].approach_axis());
    out.width = std::max(0.0, span.dot(out.closing_axis()));
  }
  return moved;
}

}  // namespace partreg::core
