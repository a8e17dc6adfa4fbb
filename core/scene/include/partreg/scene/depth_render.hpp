#pragma once
/// \file
/// Depth images of meshes as a structured-light RGB-D camera measures them, ray cast with Embree: depth noise
/// that grows with the square of the distance, quantisation in disparity, and the pixels such a sensor loses
/// (surfaces seen at grazing angles, the projector's shadows beside objects, and a band at every depth edge).
/// Everything is in the camera frame (camera.hpp: x right, y down, z forward) and metres.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "partreg/core/types.hpp"
#include "partreg/scene/camera.hpp"

namespace partreg::scene {

/// The sensor's imperfections. The defaults are a Kinect-like camera at 0.5 to 1.5 m.
struct SensorSettings {
  double noise = 0.0015;           ///< depth noise's standard deviation at 1 m (m); it grows with depth squared
  double baseline = 0.075;         ///< projector offset along +x (m): depth is quantised in its disparity
  double disparity_step = 0.125;   ///< disparity quantum (pixels): a depth step of z^2 step / (fx baseline)
  double grazing_degrees = 75.0;   ///< surfaces seen more obliquely than this (from their normal) are lost
  double edge_jump = 0.02;         ///< pixels beside a depth jump larger than this (m) are lost
  bool projector_shadows = true;   ///< pixels the projector cannot light (occluded towards +x) are lost
  std::uint64_t seed = 1;          ///< noise seed
};

/// What the camera saw.
struct RenderedDepth {
  DepthImage depth;   ///< measured depth (m; 0 = lost or nothing there)
  DepthImage clean;   ///< the true depth of the first surface hit (m; 0 = nothing there)
  std::vector<int> surface;  ///< per pixel, the index of the mesh hit first (-1 = none)
};

/// Renders `meshes` (camera frame, m). UsageError for settings out of range; InputError for a mesh without faces.
RenderedDepth render_depth(const std::vector<core::Mesh>& meshes, const Intrinsics& intrinsics,
                           const SensorSettings& sensor = {});

/// The pixels where mesh `index` is the first surface hit (lost pixels included: the object's true extent).
PixelMask surface_mask(const RenderedDepth& rendered, int index);

}  // namespace partreg::scene
