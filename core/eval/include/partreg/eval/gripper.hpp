#pragma once
/// \file
/// The gripper test: would a parallel-jaw gripper hold an object with a grasp (core/transfer/grasp.hpp)? The
/// fingers start open at max_aperture / 2 on either side of the grasp's origin along its closing axis and
/// close towards it; each finger pad is sampled by 5 rays (its centre and the middles of its four sides,
/// across y and z). A finger stops at its pad's first touch. The grasp holds when both fingers touch the
/// object before passing the origin, each first-touch surface normal lies inside the friction cone about the
/// closing axis (angle <= atan(mu)), and neither finger meets the object on its way in along the approach
/// (finger_depth behind the open pad). The same simulation samples antipodal grasps on a mesh and re-seats
/// carried grasps on what a registration believes the object is. Lengths in the object's data units.
///
/// It lives with the evaluation because the evaluation is its first judge and both cast rays with Embree.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/transfer/grasp.hpp"
#include "partreg/core/types.hpp"

namespace partreg::eval {

/// A triangle mesh to cast rays at (Embree). Building it is the expensive part; casting is thread-safe.
class MeshRays {
 public:
  /// InputError for a mesh without faces or with non-finite vertices.
  explicit MeshRays(const core::Mesh& mesh);
  ~MeshRays();
  MeshRays(MeshRays&&) noexcept;
  MeshRays& operator=(MeshRays&&) noexcept;

  struct Hit {
    double distance = 0.0;                             ///< along the (unit) direction
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit face normal, facing the ray's origin
  };
  /// The first surface met from `origin` along unit `direction` within `max_distance`.
  std::optional<Hit> first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                               double max_distance) const;

  const core::Mesh& mesh() const;

 private:
  struct Scene;
  std::unique_ptr<Scene> scene_;
};

/// What the gripper test found for one grasp.
struct GraspCheck {
  bool holds = false;
  std::string reason;  ///< why not (empty when it holds)
  Eigen::Vector3d contacts[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};  ///< first touches
  Eigen::Vector3d normals[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};   ///< facing the fingers
  bool touched[2] = {false, false};
  double angles_degrees[2] = {180.0, 180.0};  ///< each contact normal's angle to the closing axis
  double width = 0.0;                         ///< the fingers' distance when both touch (data units)
  bool collides = false;                      ///< a finger meets the object on its way in
};

/// Closes `gripper` with `grasp` on `object`. UsageError for an invalid gripper.
GraspCheck check_grasp(const MeshRays& object, const core::Grasp& grasp, const core::Gripper& gripper);

/// The quality of a checked grasp in [0, 1]: 0 unless it holds; else how far inside the friction cone the
/// worse contact lies (1 = along the axis, 0 = on the cone's edge).
double grasp_quality(const GraspCheck& check, const core::Gripper& gripper);

/// Antipodal grasps on `mesh`: surface points drawn by area (seeded), each paired with the surface met
/// along its normal (either way) within max_aperture, the pair's axis as closing axis and approaches tried
/// around it until the gripper test holds; grasps closer than half a pad to a kept one are dropped. With
/// `allowed` (one flag per face), only points on allowed faces start a grasp. At most `count` grasps (fewer
/// when the mesh offers fewer after 200 x count tries), named grasp_0, grasp_1, ..., ranked by quality.
std::vector<core::Grasp> sample_grasps(const core::Mesh& mesh, const core::Gripper& gripper, int count,
                                       std::uint64_t seed, const std::vector<bool>& allowed = {});

/// Re-seats carried grasps on `believed` (what the registration believes the object is: its deformed
/// mesh) and, where given, on `observed` points: the fingers are closed on the believed mesh along each
/// grasp's closing axis; the closing axis is turned to the mean of the two contact normals (antipodal there),
/// and the grasp's origin and width are moved to the contacts; then the observed points under each pad (within
/// half a pad of the closing line, the outermost on each side), when at least 3 per pad, move the contacts
/// to where the sensor saw the surface. A grasp the believed mesh holds less well after the move keeps its
/// carried pose. Each grasp gets its quality on the believed mesh; the list comes back ranked by quality
/// (stable).
std::vector<core::Grasp> reseat_grasps(const MeshRays& believed, const core::Points* observed,
                                       const std::vector<core::Grasp>& grasps, const core::Gripper& gripper);

}  // namespace partreg::eval
