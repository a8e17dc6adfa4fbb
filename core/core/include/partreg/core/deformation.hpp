#pragma once
/// \file
/// Carrying what is attached to the canonical onto the observed object (paper, Eq. 4): the canonical mesh,
/// any points, and frames (a grasp pose as position plus rotation). Points move by the registered
/// deformation field v(z) = G(z, C) W(x) and then by the pose. With part-based variants each part's field
/// and pose apply near that part, blended smoothly where parts meet.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "partreg/core/category_model.hpp"
#include "partreg/core/registration.hpp"

namespace partreg::core {

/// A frame attached to the canonical, in the category's data frame.
struct Frame {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< columns: the frame's axes
};

/// Moves points given in the canonical data frame into the observed frame as the registration moved the
/// canonical.
Points deform_points(const CategoryModel& model, const RegistrationResult& result,
                     const Points& canonical_points);

/// The canonical mesh deformed into the observed frame (same faces).
Mesh deform_mesh(const CategoryModel& model, const RegistrationResult& result);

/// Frames carried over: the position moves like a point; the rotation turns by the local Jacobian of the
/// deformation (I + dv/dz), orthonormalised by polar decomposition, and then by the pose.
std::vector<Frame> transfer_frames(const CategoryModel& model, const RegistrationResult& result,
                                   const std::vector<Frame>& frames);

}  // namespace partreg::core
