#pragma once
/// \file
/// A held-out object turning under a fixed depth camera, frame by frame: the stream a robot's camera gives.
/// Shared by the tracking test and the warm-frame benchmark.

#include <Eigen/Geometry>
#include <vector>

#include "partreg/core/types.hpp"
#include "partreg/eval/views.hpp"

namespace partreg::testing {

/// One frame: what the camera saw, where the camera is, and the whole object as it stands (the truth).
struct TurningFrame {
  core::Points observed;
  Eigen::Vector3d viewpoint;
  core::Points truth;
};

/// `count` frames of `object` (a dense cloud, data units) turning about `up` through its centroid by
/// `step_rad` a frame, seen from the fixed direction `camera` (unit, from the centroid). The views are cast
/// once on the unturned object from the camera's direction turned back, then turned with the object.
inline std::vector<TurningFrame> turning_sequence(const core::Points& object, const Eigen::Vector3d& up,
                                                  const Eigen::Vector3d& camera, int count, double step_rad) {
  const eval::ViewCaster caster(object);
  const Eigen::RowVector3d centre = object.colwise().mean();
  std::vector<TurningFrame> frames;
  for (int k = 0; k < count; ++k) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(step_rad * k, up.normalized()).toRotationMatrix();
    const eval::View view = caster.cast(R.transpose() * camera);
    const auto turn = [&](const core::Points& points) -> core::Points {
      return ((points.rowwise() - centre) * R.transpose()).rowwise() + centre;
    };
    frames.push_back({turn(view.points), R * (view.viewpoint - centre.transpose()) + centre.transpose(),
                      turn(object)});
  }
  return frames;
}

}  // namespace partreg::testing
