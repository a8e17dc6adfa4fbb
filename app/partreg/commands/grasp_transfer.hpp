#pragma once
/// \file
/// `register --grasps IN --grasps-out OUT`: grasps carried through a registration and re-seated on what it
/// believes the object is (the deformed canonical mesh) and on the observed points, ranked.

#include <optional>
#include <string>
#include <vector>

#include "partreg/core/transfer/grasp.hpp"

namespace partreg::app {

/// Grasps read for a registration, with the gripper that will execute them.
struct GraspRequest {
  std::vector<core::Grasp> grasps;
  core::Gripper gripper;
};

/// Reads `grasps_path` and the gripper (`gripper_path`, else the grasps file's own); InputError when neither
/// holds a gripper. Read before the registration runs, so bad files are refused before any work.
GraspRequest read_grasp_request(const std::string& grasps_path, const std::string& gripper_path);

/// Transfers and re-seats `request` (core::transfer_grasps, eval::reseat_grasps) and writes them to `path`
/// with their gripper; logs how many the believed object holds. InputError for a model without a mesh.
void write_carried_grasps(const core::CategoryModel& model, const core::RegistrationResult& result,
                          const core::Points& observed, const GraspRequest& request, const std::string& path);

}  // namespace partreg::app
