#pragma once
/// \file
/// Free space: what a depth camera says about where the object is not. A pixel's ray passed through empty
/// space up to the depth it measured, so a model point that projects onto that pixel clearly in front of the
/// measured depth contradicts the image. The camera is a pinhole in OpenCV's convention (x right, y down,
/// z forward; pixel (u, v) is column u, row v, its centre at integer coordinates). Lengths are in the
/// observation's units: metres for a depth camera, which the noise defaults assume (docs/camera.md,
/// "Free space").

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "partreg/core/types.hpp"

namespace partreg::core {

/// A depth image with its pinhole intrinsics and its sensor's noise, judging points against it.
struct FreeSpace {
  double fx = 0.0, fy = 0.0;  ///< focal lengths (pixels)
  double cx = 0.0, cy = 0.0;  ///< principal point (pixels)
  /// Measured depth along the optical axis per pixel (rows = image height, columns = width; observation
  /// units); 0 or NaN where the sensor measured nothing.
  Eigen::MatrixXf depth;
  /// The depth noise's standard deviation is noise_offset + noise_quadratic z^2. The quadratic term is the
  /// structured-light sensor `partreg scene` renders (0.0015 m at 1 m, a Kinect-class camera's); the
  /// offset covers its disparity quantisation (1/8 pixel: 1 mm at 0.6 m).
  double noise_offset = 0.001;      ///< (observation units)
  double noise_quadratic = 0.0015;  ///< (per observation unit)
  /// A point violates only this many standard deviations in front of the measured depth, or more.
  double noise_multiple = 3.0;
  /// ... and beyond this, too (observation units): a correct registration's surface lies a few millimetres
  /// off the measured one on a mug (about 2% of its 0.15 m diagonal), which must not read as a violation.
  double margin = 0.005;
  /// A point on a measured pixel is judged against the smallest depth measured within this many pixels of
  /// it: one a pixel or two across a silhouette from where the object was measured (a correct fit's lateral
  /// error, 2 mm at 0.6 m) meets the object's depth there, not the table's far behind it.
  int lateral_window = 2;
  /// A pixel without a return stands for the smallest depth measured within this many pixels: the rendered
  /// sensor loses bands of a mug's silhouette at grazing angles and beside depth jumps, and its projector's
  /// shadow (the mug's inside), and a hole in a surface is not free space. With none measured that close the
  /// pixel's ray met nothing: it is free all along.
  int missing_window = 15;
  /// Maps the frame of the points judged (the observation given to registration) into the camera frame: the
  /// identity when the observation is in the camera frame; a rotation for the scene's up-aligned frame; a
  /// similarity inside registration, whose fits work in normalised units.
  Eigen::Affine3d T_camera_observed = Eigen::Affine3d::Identity();

  int width() const { return static_cast<int>(depth.cols()); }
  int height() const { return static_cast<int>(depth.rows()); }
  /// The depth noise's standard deviation at depth z (observation units).
  double sigma(double z) const { return noise_offset + noise_quadratic * z * z; }
  /// The depth that stands for pixel (u, v): the smallest measured within lateral_window pixels of a measured
  /// pixel, within missing_window pixels of a lost one; 0 where none (the ray met nothing).
  double depth_at(int u, int v) const;
  /// How far a camera-frame point lies in front of the depth its pixel stands for, beyond the allowance
  /// (noise_multiple sigma(depth) + margin); 0 for a point behind that or within it, outside the image or
  /// behind the camera; infinity on a pixel whose ray met nothing (observation units).
  double violation(const Eigen::Vector3d& point_in_camera) const;
  /// The share of `points` (observation frame, T_camera_observed maps them) that violate; 0 for none.
  double violation_share(const Points& points_in_observed) const;
  /// The same free space with every pixel's stand-in depth (depth_at) written into `depth` and both windows
  /// 0: one read per point, for the thousands of tests a pose search makes.
  FreeSpace prepared() const;
  /// InputError for non-finite or non-positive focal lengths, an empty image, negative depth, noise or
  /// windows.
  void validate() const;
};

}  // namespace partreg::core
