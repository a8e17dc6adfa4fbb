#include "partreg/core/deformation.hpp"

#include <Eigen/SVD>
#include <algorithm>

#include "partreg/core/errors.hpp"
#include "partreg/core/gaussian_kernel.hpp"
#include "partreg/core/kdtree.hpp"
#include "partreg/core/sampling.hpp"
#include "partreg/core/space_walk.hpp"
#include "seam_agreement.hpp"

namespace partreg::core {
namespace {

using detail::smoothstep;

// The spaces whose fields move the points: holistic alone, or every part.
std::vector<std::size_t> active_spaces(const RegistrationResult& result) {
  std::vector<std::size_t> spaces;
  for (std::size_t f = 0; f < result.fits.size(); ++f)
    if (result.variant == Variant::holistic ? f == 0 : result.fits[f].space != "holistic")
      spaces.push_back(f);
  if (spaces.empty()) throw UsageError("the registration result holds no space to deform with");
  return spaces;
}

const ShapeSpace& space_of(const CategoryModel& model, const SpaceFit& fit) { return model.space(fit.space); }

Eigen::MatrixXd blend_weights(const CategoryModel& model, const RegistrationResult& result,
                              const std::vector<std::size_t>& spaces, const Points& normalised,
                              const SeamBlend& blend) {
  std::vector<const ShapeSpace*> blended;
  for (std::size_t s : spaces) blended.push_back(&space_of(model, result.fits[s]));
  return seam_weights(blended, normalised, blend);
}

// One space's motion of normalised canonical points, ending in the observed data frame.
Points moved_by(const CategoryModel& model, const SpaceFit& fit, const Points& normalised) {
  const ShapeSpace& space = space_of(model, fit);
  const Points displaced =
      normalised + apply_kernel(normalised, space.canonical, space.weights(fit.latent), space.beta);
  const Points data = model.normalization.undo(displaced);
  const Eigen::Matrix3d linear = fit.T_observed_canonical.topLeftCorner<3, 3>();
  return (data * linear.transpose()).rowwise() + fit.T_observed_canonical.topRightCorner<3, 1>().transpose();
}

// The rotation nearest a linear map (polar decomposition), kept proper.
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& linear) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(linear, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d rotation = svd.matrixU() * svd.matrixV().transpose();
  if (rotation.determinant() < 0.0)
    rotation = svd.matrixU() * Eigen::Vector3d(1, 1, -1).asDiagonal() * svd.matrixV().transpose();
  return rotation;
}

}  // namespace

Eigen::MatrixXd seam_weights(const std::vector<const ShapeSpace*>& spaces, const Points& normalised,
                             const SeamBlend& blend) {
  if (spaces.empty()) throw UsageError("seam blending needs at least one space");
  if (!(blend.band >= 0.0)) throw UsageError("the seam band must be zero or positive");
  const auto count = static_cast<Eigen::Index>(spaces.size());
  Eigen::MatrixXd distance(normalised.rows(), count);
  for (Eigen::Index s = 0; s < count; ++s) {
    const KdTree tree(spaces[static_cast<std::size_t>(s)]->canonical);
    std::vector<int> index;
    Eigen::VectorXd squared;
    tree.nearest_all(normalised, index, squared);
    distance.col(s) = squared.cwiseSqrt();
  }
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(normalised.rows(), count);
  for (Eigen::Index i = 0; i < normalised.rows(); ++i) {
    Eigen::Index nearest = 0;
    const double closest = distance.row(i).minCoeff(&nearest);
    if (blend.band == 0.0) {
      weights(i, nearest) = 1.0;
      continue;
    }
    // The nearest space weighs 1, so the sum is at least 1 and the division is safe.
    for (Eigen::Index s = 0; s < count; ++s)
      weights(i, s) = smoothstep(1.0 - (distance(i, s) - closest) / blend.band);
    weights.row(i) /= weights.row(i).sum();
  }
  return weights;
}

Points deform_points(const CategoryModel& model, const RegistrationResult& result,
                     const Points& canonical_points, const SeamBlend& blend) {
  const Points normalised = model.normalization.apply(canonical_points);
  const std::vector<std::size_t> spaces = active_spaces(result);
  const Eigen::MatrixXd weights = blend_weights(model, result, spaces, normalised, blend);
  Points moved = Points::Zero(canonical_points.rows(), 3);
  for (std::size_t s = 0; s < spaces.size(); ++s)
    moved += weights.col(static_cast<Eigen::Index>(s)).asDiagonal() *
             moved_by(model, result.fits[spaces[s]], normalised);
  // The refinement's field lives where the space put the points (observed frame).
  return moved + result.refinement.displacement_at(moved);
}

Mesh deform_mesh(const CategoryModel& model, const RegistrationResult& result, const SeamBlend& blend) {
  Mesh mesh;
  mesh.vertices =
      deform_points(model, result, model.normalization.undo(model.canonical_mesh.vertices), blend);
  mesh.faces = model.canonical_mesh.faces;
  return mesh;
}

double mesh_stretch(const CategoryModel& model, const RegistrationResult& result) {
  if (model.canonical_mesh.faces.rows() == 0) return 0.0;
  // The canonical mesh is in normalised units, the deformed one in observation units.
  return max_edge_stretch(model.canonical_mesh, deform_mesh(model, result).vertices / model.observed_diagonal());
}

SeamGap seam_gap(const CategoryModel& model, const RegistrationResult& result, double radius) {
  SeamGap gap;
  if (result.variant == Variant::holistic) return gap;
  const std::vector<std::size_t> parts = active_spaces(result);
  double total = 0.0;
  for (std::size_t a = 0; a < parts.size(); ++a)
    for (std::size_t b = 0; b < parts.size(); ++b) {
      if (a == b) continue;
      const SpaceFit& own = result.fits[parts[a]];
      const SpaceFit& other = result.fits[parts[b]];
      const Points& own_points = space_of(model, own).canonical;
      const KdTree other_tree(space_of(model, other).canonical);
      std::vector<int> boundary;
      for (Eigen::Index i = 0; i < own_points.rows(); ++i)
        if (other_tree.nearest(own_points.row(i).transpose()).second <= radius * radius)
          boundary.push_back(static_cast<int>(i));
      if (boundary.empty()) continue;
      const Points z = select_rows(own_points, boundary);
      const Eigen::VectorXd distance =
          (moved_by(model, own, z) - moved_by(model, other, z)).rowwise().norm() / model.observed_diagonal();
      gap.max = std::max(gap.max, distance.maxCoeff());
      total += distance.sum();
      gap.points += static_cast<int>(distance.size());
    }
  if (gap.points > 0) gap.mean = total / gap.points;
  return gap;
}

SeamGap training_seam_gap(const CategoryModel& model, double radius) {
  SeamGap gap;
  if (!model.has_parts()) return gap;
  const Eigen::Index instances = model.holistic().training_latents.rows();
  for (Eigen::Index i = 0; i < instances; ++i) {
    RegistrationResult at_instance;
    at_instance.variant = Variant::partwise;
    for (std::size_t s = 1; s < model.spaces.size(); ++s) {
      SpaceFit fit;
      fit.space = model.spaces[s].name;
      fit.latent = model.spaces[s].training_latents.row(i).transpose();
      at_instance.fits.push_back(fit);
    }
    const SeamGap own = seam_gap(model, at_instance, radius);
    gap.mean += own.mean / static_cast<double>(instances);
    gap.max = std::max(gap.max, own.max);
    gap.points = own.points;
  }
  return gap;
}

std::vector<Frame> transfer_frames(const CategoryModel& model, const RegistrationResult& result,
                                   const std::vector<Frame>& frames) {
  const std::vector<std::size_t> spaces = active_spaces(result);
  std::vector<Frame> moved;
  for (const Frame& frame : frames) {
    Points position(1, 3);
    position.row(0) = frame.position.transpose();
    const Points normalised = model.normalization.apply(position);
    // The rotation follows the space that dominates at the frame (no averaging of rotations).
    Eigen::Index dominant = 0;
    blend_weights(model, result, spaces, normalised, {}).row(0).maxCoeff(&dominant);
    const SpaceFit& fit = result.fits[spaces[static_cast<std::size_t>(dominant)]];
    const ShapeSpace& space = space_of(model, fit);
    const Eigen::Matrix3d jacobian =
        Eigen::Matrix3d::Identity() + kernel_field_jacobian(normalised.row(0).transpose(), space.canonical,
                                                            space.weights(fit.latent), space.beta);
    // The pose's rotation without its scale (the fitted one, and a model's real size's).
    const Eigen::Matrix3d pose_rotation = nearest_rotation(fit.T_observed_canonical.topLeftCorner<3, 3>());
    // The refinement turns the frame by its own Jacobian where the space put it, after the pose.
    const Eigen::Vector3d by_space = moved_by(model, fit, normalised).row(0).transpose();
    const Eigen::Matrix3d refinement = Eigen::Matrix3d::Identity() + result.refinement.jacobian_at(by_space);
    Frame out = frame;
    out.position = deform_points(model, result, position).row(0).transpose();
    out.rotation = nearest_rotation(refinement) * pose_rotation * nearest_rotation(jacobian) * frame.rotation;
    moved.push_back(out);
  }
  return moved;
}

}  // namespace partreg::core
