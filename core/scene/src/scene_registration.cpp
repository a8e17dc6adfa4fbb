#include "partreg/scene/scene_registration.hpp"

#include <algorithm>
#include <cmath>

namespace partreg::scene {

core::RegistrationResult rotated(core::RegistrationResult result, const Eigen::Matrix3d& R) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R;
  for (core::SpaceFit& fit : result.fits) fit.T_observed_canonical = T * fit.T_observed_canonical;
  for (core::HistoryStep& step : result.history) step.T_observed_canonical = T * step.T_observed_canonical;
  result.deformed = result.deformed * R.transpose();
  // v(p) = sum g(|p - c|) w is isotropic in p, so the turned field has turned centres and turned weights.
  result.refinement.centres = result.refinement.centres * R.transpose();
  result.refinement.weights = result.refinement.weights * R.transpose();
  return result;
}

core::RegistrationResult register_cut(const core::CategoryModel& model, const SceneCut& cut,
                                      core::RegistrationSettings settings, const SceneRegistrationSettings& scene,
                                      const core::ProgressListener& progress) {
  settings.viewpoint = Eigen::Vector3d::Zero();  // the camera, in both frames: the turn keeps the origin
  if (!settings.free_space) settings.free_space = cut.free_space;
  if (!(cut.up.norm() > 0)) return core::register_observation(model, cut.object.points, settings, progress);
  const Eigen::Vector3d model_up = settings.initialisation.up.value_or(model.up).normalized();
  const Eigen::Matrix3d R_upright_camera =
      Eigen::Quaterniond::FromTwoVectors(cut.up.normalized(), model_up).toRotationMatrix();
  if (!scene.search_tilts) {
    settings.initialisation.max_tilt = 0.0;
    settings.initialisation.any_rotation = false;
    settings.initialisation.align_principal_axes = false;
  }
  if (settings.free_space) {
    // The free-space test reads camera-frame points: the upright ones are turned back first.
    auto upright_free = std::make_shared<core::FreeSpace>(*settings.free_space);
    upright_free->T_camera_observed = settings.free_space->T_camera_observed * R_upright_camera.transpose();
    settings.free_space = std::move(upright_free);
  }
  const core::Points upright = cut.object.points * R_upright_camera.transpose();
  return rotated(core::register_observation(model, upright, settings, progress), R_upright_camera.transpose());
}

double up_axis_angle_degrees(const core::CategoryModel& model, const core::RegistrationResult& result,
                             const Eigen::Vector3d& up) {
  const Eigen::Matrix3d R = result.fits.front().T_observed_canonical.topLeftCorner<3, 3>();
  const Eigen::Vector3d model_up = (R * model.up).normalized();
  return std::acos(std::clamp(model_up.dot(up.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace partreg::scene
