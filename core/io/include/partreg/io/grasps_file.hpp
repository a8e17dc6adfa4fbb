#pragma once
/// \file
/// Parallel-jaw grasps and their gripper (core/transfer/grasp.hpp), as JSON:
/// {"format": "partreg-grasps", "version": 1,
///  "gripper": {"max_aperture": 0.08, "pad_size": 0.02, "finger_depth": 0.04, "friction": 0.5},
///  "grasps": [{"name": "grasp_0", "part": "handle", "position": [x, y, z],
///              "rotation": [[r00, r01, r02], [r10, r11, r12], [r20, r21, r22]], "width": 0.03,
///              "quality": 0.8}]}
/// Rotation columns are the closing (x), pad (y) and approach (z) axes; lengths in the data units of the
/// object (the category's data frame for canonical grasps, the observed frame after `partreg register`).
/// "relative_to_diagonal": true (optional, default false) gives the gripper's lengths as fractions of the
/// object's bounding-box diagonal (core::Gripper::relative). "gripper" is optional in a grasps file; a gripper file is {"format": "partreg-gripper", "version": 1, ...}
/// with the gripper's fields at the top level. "part" and "quality" are optional.

#include <filesystem>
#include <optional>
#include <vector>

#include "partreg/core/transfer/grasp.hpp"

namespace partreg::io {

struct GraspsFile {
  std::vector<core::Grasp> grasps;
  std::optional<core::Gripper> gripper;
};

/// Reads grasps; InputError naming the file and grasp for malformed JSON, non-finite numbers, a negative
/// width or a rotation that is not proper orthonormal (|R^T R - I| > 1e-6 or det R < 0).
GraspsFile read_grasps_file(const std::filesystem::path& path);

/// Writes grasps (with their gripper, when given) atomically.
void write_grasps_file(const std::filesystem::path& path, const std::vector<core::Grasp>& grasps,
                       const std::optional<core::Gripper>& gripper);

/// A gripper from a gripper file or from a grasps file's "gripper"; InputError when it holds none, UsageError
/// for values out of range (core::validate).
core::Gripper read_gripper_file(const std::filesystem::path& path);

}  // namespace partreg::io
