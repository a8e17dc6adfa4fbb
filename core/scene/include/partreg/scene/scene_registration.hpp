#pragma once
/// \file
/// Registering an object cut out of a scene (segmentation.hpp), in the camera frame. The viewpoint is the
/// camera's origin. The pose search turns about the scene's up axis only: the cut cloud is turned into a frame
/// whose up axis is the model's (CategoryModel::up), registered there without tilts of the up axis, and the
/// result turned back, so every pose, point and field in the result is in the camera frame.

#include <Eigen/Geometry>

#include "partreg/core/registration/registration.hpp"
#include "partreg/scene/segmentation.hpp"

namespace partreg::scene {

/// What the scene adds to a registration request.
struct SceneRegistrationSettings {
  /// Also try tilts of the up axis (InitialisationSettings::max_tilt as given) rather than turning about the
  /// table's normal only: for an object that may lie on its side.
  bool search_tilts = false;
};

/// Registers `model` onto `cut.object` (camera frame, data units of the model). `settings.viewpoint` is
/// replaced by the camera's origin; `settings.free_space` (camera frame), when empty, is the cut's. Throws
/// what register_observation throws.
core::RegistrationResult register_cut(const core::CategoryModel& model, const SceneCut& cut,
                                      core::RegistrationSettings settings,
                                      const SceneRegistrationSettings& scene = {},
                                      const core::ProgressListener& progress = {});

/// `result` with every pose, point and field mapped by the rotation `R_to_from` (from the frame it was
/// computed in to another with the same origin).
core::RegistrationResult rotated(core::RegistrationResult result, const Eigen::Matrix3d& R_to_from);

/// The angle (degrees) between the registered object's up axis (the model's, turned by the holistic pose)
/// and `up` (camera frame).
double up_axis_angle_degrees(const core::CategoryModel& model, const core::RegistrationResult& result,
                             const Eigen::Vector3d& up);

}  // namespace partreg::scene
