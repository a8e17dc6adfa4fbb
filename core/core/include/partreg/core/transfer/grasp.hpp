#pragma once
/// \file
/// Parallel-jaw grasps attached to the canonical, and the gripper that executes them. A grasp is a pose
/// whose x axis is the closing axis (the fingers move towards each other along it), whose z axis is the
/// approach (from the palm towards the object) and whose origin is the point midway between the fingers'
/// contacts; y = z x x runs across the finger pads. Lengths are in the data units of the object the grasp
/// belongs to (the category's data frame for a canonical grasp).
///
/// Carrying a grasp through a registration (transfer_grasps) moves its two contacts as material points and
/// turns its axes with the region around them (deformation.hpp, region_rotations): the grasp follows the
/// material it touches. Ray-cast tests of whether a gripper holds (the gripper test), sampling and
/// re-seating on a surface live in partreg_grasp (partreg/grasp/), above the core.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "partreg/core/registration/registration.hpp"
#include "partreg/core/space/category_model.hpp"

namespace partreg::core {

/// A parallel-jaw gripper. Defaults: a Franka Panda hand's fingers at the scale of a 0.3-unit object.
struct Gripper {
  double max_aperture = 0.08;  ///< widest opening between the finger pads (data units)
  double pad_size = 0.02;      ///< side of a square finger pad (data units)
  /// length of a finger behind its pad, back along -z towards the palm: the approach must be free of the
  /// object over it (data units)
  double finger_depth = 0.04;
  double friction = 0.5;       ///< Coulomb coefficient mu: a contact holds within atan(mu) of the closing axis
  /// The lengths above are fractions of the object's bounding-box diagonal, not data units: one gripper
  /// file then serves categories of any size (the evaluation's default). in_units() makes them absolute.
  bool relative = false;

  /// This gripper with absolute lengths for an object of `diagonal` (data units); itself when absolute.
  Gripper in_units(double diagonal) const;
};

/// One grasp. Its axes are the columns of `rotation` (see the file comment).
struct Grasp {
  std::string name;
  std::string part;  ///< the part the grasp belongs to; empty when the model has none
  Eigen::Vector3d position = Eigen::Vector3d::Zero();       ///< midway between the contacts (data units)
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();   ///< columns x (closing), y (pad), z (approach)
  double width = 0.0;    ///< distance between the contacts (data units)
  double quality = 0.0;  ///< in [0, 1]: 1 = both contact normals along the closing axis; 0 = not held

  Eigen::Vector3d closing_axis() const { return rotation.col(0); }
  Eigen::Vector3d approach_axis() const { return rotation.col(2); }
  /// The two contacts, -x side first: position -+ width / 2 along the closing axis.
  Eigen::Vector3d contact(int side) const { return position + (side == 0 ? -0.5 : 0.5) * width * closing_axis(); }
};

/// Checks a gripper's numbers: finite and positive lengths, friction >= 0. UsageError naming the field.
void validate(const Gripper& gripper);

/// The width of the region a grasp's axes turn with (normalised length): two pads. On a held-out real mug
/// (30 grasps of a 0.35-diagonal gripper) carried grasps held 15 with half a pad, 20 with two, 19 with the
/// pose's rotation alone. `gripper` in observation units (Gripper::in_units(model.observed_diagonal())).
double grasp_region_radius(const CategoryModel& model, const Gripper& gripper);

/// Grasps on the canonical carried onto the observed object: both contacts move as material points
/// (deform_points, Follow::material) and the origin goes midway between them; the axes turn with the region
/// around both contacts (region_rotations, grasp_region_radius); the width is the carried contacts' distance
/// along the turned closing axis. Quality is kept: re-seating (eval/gripper.hpp) measures it anew.
std::vector<Grasp> transfer_grasps(const CategoryModel& model, const RegistrationResult& result,
                                   const std::vector<Grasp>& grasps, const Gripper& gripper);

/// A proper rotation whose x axis is `closing` and whose z axis is `approach` made perpendicular to it (the
/// nearest such); when they are parallel, any perpendicular z. Both need not be unit.
Eigen::Matrix3d grasp_axes(const Eigen::Vector3d& closing, const Eigen::Vector3d& approach);

}  // namespace partreg::core
