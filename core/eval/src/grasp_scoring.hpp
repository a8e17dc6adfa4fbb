#pragma once
// Grasps in the evaluation (internal to partreg_eval): the canonical grasps of a fold, carried by a
// registration or rigidly, judged on the true mesh by the gripper test (gripper.hpp).

#include <optional>
#include <vector>

#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/space/category_model.hpp"
#include "partreg/core/transfer/grasp.hpp"
#include "partreg/eval/gripper.hpp"
#include "partreg/eval/protocol.hpp"

namespace partreg::eval::detail {

/// The fold's canonical grasps: the given ones, or `count` sampled with `gripper` (absolute units) on the canonical mesh (seeded), each with
/// the part of its nearest canonical mesh vertex. Empty for a model without a mesh.
std::vector<core::Grasp> fold_grasps(const core::CategoryModel& model, const core::Gripper& gripper,
                                     const GraspEvaluation& settings, std::uint64_t seed);

/// One observation's grasp judging: the fold's canonical grasps and what they are judged against.
struct GraspJudge {
  const std::vector<core::Grasp>* canonical = nullptr;
  const core::Gripper* gripper = nullptr;
  const MeshRays* true_mesh = nullptr;    ///< the true instance's mesh, in the observed frame
  const core::KdTree* truth = nullptr;    ///< the true surface's points, in the observed frame
  double diagonal = 0.0;                  ///< the truth's diagonal
  const core::Points* observed = nullptr;
  const core::Points* truth_of_row = nullptr;  ///< true correspondents of the canonical rows, or null
};

/// The grasps `result` carries (core::transfer_grasps), re-seated on its deformed mesh and the observation,
/// judged on the truth; with true correspondents, the frame errors of the transfer too.
GraspScore registration_grasps(const GraspJudge& judge, const core::CategoryModel& model,
                               const core::RegistrationResult& result);

/// The canonical grasps moved rigidly by T_observed_canonical (the rigid canonical baseline), judged.
GraspScore rigid_grasps(const GraspJudge& judge, const core::CategoryModel& model,
                        const Eigen::Matrix4d& T_observed_canonical);

}  // namespace partreg::eval::detail
