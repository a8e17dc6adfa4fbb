#include "partreg/core/deformation.hpp"

#include <Eigen/SVD>

#include "partreg/core/errors.hpp"
#include "partreg/core/gaussian_kernel.hpp"
#include "partreg/core/kdtree.hpp"

namespace partreg::core {
namespace {

constexpr double kSeamWidth = 0.02;  // normalised: how far a part's field reaches into its neighbour's

// The spaces whose fields move the points: holistic alone, or every part.
std::vector<std::size_t> active_spaces(const CategoryModel& model, const RegistrationResult& result) {
  std::vector<std::size_t> spaces;
  for (std::size_t f = 0; f < result.fits.size(); ++f)
    if (result.variant == Variant::holistic ? f == 0 : result.fits[f].space != "holistic")
      spaces.push_back(f);
  if (spaces.empty()) throw UsageError("the registration result holds no space to deform with");
  (void)model;
  return spaces;
}

const ShapeSpace& space_of(const CategoryModel& model, const SpaceFit& fit) { return model.space(fit.space); }

// Blend weights of each active space at each point: a Gaussian of the distance to that space's canonical
// points.
Eigen::MatrixXd blend_weights(const CategoryModel& model, const RegistrationResult& result,
                              const std::vector<std::size_t>& spaces, const Points& normalised) {
  Eigen::MatrixXd weights(normalised.rows(), static_cast<Eigen::Index>(spaces.size()));
  for (std::size_t s = 0; s < spaces.size(); ++s) {
    const KdTree tree(space_of(model, result.fits[spaces[s]]).canonical);
    std::vector<int> index;
    Eigen::VectorXd squared;
    tree.nearest_all(normalised, index, squared);
    weights.col(static_cast<Eigen::Index>(s)) = (-0.5 * squared.array() / (kSeamWidth * kSeamWidth)).exp();
  }
  // Points far from every part keep the nearest one's field rather than dividing by zero.
  for (Eigen::Index i = 0; i < weights.rows(); ++i) {
    const double total = weights.row(i).sum();
    if (total > 1e-300) {
      weights.row(i) /= total;
    } else {
      Eigen::Index best = 0;
      weights.row(i).maxCoeff(&best);
      weights.row(i).setZero();
      weights(i, best) = 1.0;
    }
  }
  return weights;
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

}  // namespace

Points deform_points(const CategoryModel& model, const RegistrationResult& result,
                     const Points& canonical_points) {
  const Points normalised = model.normalization.apply(canonical_points);
  const std::vector<std::size_t> spaces = active_spaces(model, result);
  const Eigen::MatrixXd weights = blend_weights(model, result, spaces, normalised);
  Points moved = Points::Zero(canonical_points.rows(), 3);
  for (std::size_t s = 0; s < spaces.size(); ++s)
    moved += weights.col(static_cast<Eigen::Index>(s)).asDiagonal() *
             moved_by(model, result.fits[spaces[s]], normalised);
  return moved;
}

Mesh deform_mesh(const CategoryModel& model, const RegistrationResult& result) {
  Mesh mesh;
  mesh.vertices = deform_points(model, result, model.normalization.undo(model.canonical_mesh.vertices));
  mesh.faces = model.canonical_mesh.faces;
  return mesh;
}

std::vector<Frame> transfer_frames(const CategoryModel& model, const RegistrationResult& result,
                                   const std::vector<Frame>& frames) {
  const std::vector<std::size_t> spaces = active_spaces(model, result);
  std::vector<Frame> moved;
  for (const Frame& frame : frames) {
    Points position(1, 3);
    position.row(0) = frame.position.transpose();
    const Points normalised = model.normalization.apply(position);
    // The rotation follows the space that dominates at the frame (no averaging of rotations).
    Eigen::Index dominant = 0;
    blend_weights(model, result, spaces, normalised).row(0).maxCoeff(&dominant);
    const SpaceFit& fit = result.fits[spaces[static_cast<std::size_t>(dominant)]];
    const ShapeSpace& space = space_of(model, fit);
    const Eigen::Matrix3d jacobian =
        Eigen::Matrix3d::Identity() + kernel_field_jacobian(normalised.row(0).transpose(), space.canonical,
                                                            space.weights(fit.latent), space.beta);
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(jacobian, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d local = svd.matrixU() * svd.matrixV().transpose();
    if (local.determinant() < 0.0)
      local = svd.matrixU() * Eigen::Vector3d(1, 1, -1).asDiagonal() * svd.matrixV().transpose();
    const Eigen::Matrix3d pose_rotation = fit.T_observed_canonical.topLeftCorner<3, 3>() / fit.scale;
    Frame out = frame;
    out.position = deform_points(model, result, position).row(0).transpose();
    out.rotation = pose_rotation * local * frame.rotation;
    moved.push_back(out);
  }
  return moved;
}

}  // namespace partreg::core
