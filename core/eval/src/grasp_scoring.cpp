#include "grasp_scoring.hpp"

#include <algorithm>
#include <cmath>

#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/registration/deformation.hpp"

namespace partreg::eval::detail {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<std::size_t>(std::floor(p * values.size())))];
}

double rotation_angle_degrees(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const double cosine = std::clamp(((a * b.transpose()).trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(cosine) * 180.0 / M_PI;
}

}  // namespace

std::vector<core::Grasp> fold_grasps(const core::CategoryModel& model, const core::Gripper& gripper,
                                     const GraspEvaluation& settings, std::uint64_t seed) {
  if (!settings.given.empty()) return settings.given;
  if (model.canonical_mesh.faces.rows() == 0) return {};
  core::Mesh mesh = model.canonical_mesh;
  mesh.vertices = model.normalization.undo(mesh.vertices);
  std::vector<core::Grasp> grasps = sample_grasps(mesh, gripper, settings.count, seed);
  if (model.has_parts() && model.mesh_vertex_part.size() == mesh.vertices.rows()) {
    const core::KdTree vertices(mesh.vertices);
    for (core::Grasp& grasp : grasps)
      grasp.part = model.part_names[static_cast<std::size_t>(
          model.mesh_vertex_part[vertices.nearest(grasp.contact(0)).first])];
  }
  return grasps;
}

namespace {

GraspScore score_grasps(const MeshRays& true_mesh, const core::KdTree& truth, double diagonal,
                        const std::vector<core::Grasp>& carried, const core::Gripper& gripper) {
  GraspScore score;
  std::vector<double> angles;
  double contact_distance = 0.0;
  for (const core::Grasp& grasp : carried) {
    const GraspCheck check = check_grasp(true_mesh, grasp, gripper);
    ++score.count;
    auto& part = score.by_part[grasp.part];
    ++part.second;
    if (check.holds) ++score.held, ++part.first;
    for (int side = 0; side < 2; ++side) {
      contact_distance += std::sqrt(truth.nearest(grasp.contact(side)).second);
      if (check.touched[side]) angles.push_back(check.angles_degrees[side]);
    }
  }
  if (score.count > 0) score.contact_per_diagonal = contact_distance / (2.0 * score.count * diagonal);
  score.axis_angle_degrees = median(angles);
  return score;
}

void add_frame_errors(GraspScore& score, const core::CategoryModel& model,
                      const std::vector<core::Grasp>& canonical, const std::vector<core::Grasp>& carried,
                      const core::Points& truth_of_row, const core::Gripper& gripper) {
  const double radius = core::grasp_region_radius(model, gripper);
  std::vector<core::Points> anchors;
  for (const core::Grasp& grasp : canonical) {
    core::Points contacts(2, 3);
    contacts.row(0) = grasp.contact(0).transpose();
    contacts.row(1) = grasp.contact(1).transpose();
    anchors.push_back(contacts);
  }
  const std::vector<core::Region> regions = core::frame_regions(model, anchors, radius);
  std::vector<double> errors;
  for (std::size_t g = 0; g < canonical.size() && g < carried.size(); ++g) {
    const core::Points before = model.normalization.undo(core::select_rows(model.canonical, regions[g].rows));
    const core::Points after = core::select_rows(truth_of_row, regions[g].rows);
    const Eigen::Matrix3d turn = core::region_motion(before, after, regions[g].weights, Eigen::Matrix3d::Identity());
    // The true grasp frame: the canonical closing axis as the true contacts move, the approach turned.
    const Eigen::Matrix3d truth = core::grasp_axes(turn * canonical[g].closing_axis(), turn * canonical[g].approach_axis());
    errors.push_back(rotation_angle_degrees(carried[g].rotation, truth));
  }
  score.frame_error_median_degrees = median(errors);
  score.frame_error_p90_degrees = percentile(errors, 0.9);
}

}  // namespace

GraspScore registration_grasps(const GraspJudge& judge, const core::CategoryModel& model,
                               const core::RegistrationResult& result) {
  const std::vector<core::Grasp> transferred =
      core::transfer_grasps(model, result, *judge.canonical, *judge.gripper);
  const MeshRays believed(core::deform_mesh(model, result));
  const std::vector<core::Grasp> seated = reseat_grasps(believed, judge.observed, transferred, *judge.gripper);
  GraspScore score = score_grasps(*judge.true_mesh, *judge.truth, judge.diagonal, seated, *judge.gripper);
  if (judge.truth_of_row)
    add_frame_errors(score, model, *judge.canonical, transferred, *judge.truth_of_row, *judge.gripper);
  return score;
}

GraspScore rigid_grasps(const GraspJudge& judge, const core::CategoryModel& model,
                        const Eigen::Matrix4d& T_observed_canonical) {
  const Eigen::Matrix3d rotation = T_observed_canonical.topLeftCorner<3, 3>();
  std::vector<core::Grasp> moved = *judge.canonical;
  for (core::Grasp& grasp : moved) {
    grasp.position = rotation * grasp.position + T_observed_canonical.topRightCorner<3, 1>();
    grasp.rotation = rotation * grasp.rotation;
  }
  GraspScore score = score_grasps(*judge.true_mesh, *judge.truth, judge.diagonal, moved, *judge.gripper);
  if (judge.truth_of_row) add_frame_errors(score, model, *judge.canonical, moved, *judge.truth_of_row, *judge.gripper);
  return score;
}

}  // namespace partreg::eval::detail

