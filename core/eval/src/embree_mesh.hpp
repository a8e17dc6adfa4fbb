#pragma once
// A triangle mesh as an Embree geometry (internal to partreg_eval): the views' caster and the gripper test
// cast rays at the same kind of scene.

#include <embree3/rtcore.h>

#include "partreg/core/types.hpp"

namespace partreg::eval::detail {

/// A new, uncommitted triangle geometry of `device` holding `mesh` (single precision, as Embree stores it).
inline RTCGeometry triangle_geometry(RTCDevice device, const core::Mesh& mesh) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.rows()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.faces.rows()));
  for (Eigen::Index i = 0; i < mesh.vertices.size(); ++i) vertices[i] = static_cast<float>(mesh.vertices.data()[i]);
  for (Eigen::Index i = 0; i < mesh.faces.size(); ++i) indices[i] = static_cast<unsigned>(mesh.faces.data()[i]);
  return geometry;
}

}  // namespace partreg::eval::detail
