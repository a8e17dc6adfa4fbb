#include "partreg/core/registration/deformation.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <map>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/registration/space_walk.hpp"
#include "geometry/mesh_relaxation.hpp"
#include "space/seam_agreement.hpp"

namespace partreg::core {
namespace {

using detail::smoothstep;

// Canonical points a frame's region takes at least, nearest first, so a sparse neighbourhood still fixes a
// rotation.
constexpr int kMinimumRegionPoints = 8;
// The pose rotation's share in the region's cross-covariance: enough to fix an axis the region leaves free,
// too little to turn a region that fixes all three.
constexpr double kPosePrior = 1e-3;

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
                     const Points& canonical_points, const SeamBlend& blend, Follow follow) {
  const Points normalised = model.normalization.apply(canonical_points);
  const std::vector<std::size_t> spaces = active_spaces(result);
  const Eigen::MatrixXd weights = blend_weights(model, result, spaces, normalised, blend);
  Points moved = Points::Zero(canonical_points.rows(), 3);
  for (std::size_t s = 0; s < spaces.size(); ++s)
    moved += weights.col(static_cast<Eigen::Index>(s)).asDiagonal() *
             moved_by(model, result.fits[spaces[s]], normalised);
  // The refinement's field lives where the space put the points (observed frame).
  return moved + (follow == Follow::surface ? result.refinement.displacement_at(moved)
                                            : result.refinement.material_displacement_at(moved));
}

Mesh deform_mesh(const CategoryModel& model, const RegistrationResult& result, const SeamBlend& blend) {
  Mesh mesh;
  mesh.faces = model.canonical_mesh.faces;
  const Points moved =
      deform_points(model, result, model.normalization.undo(model.canonical_mesh.vertices), blend);
  // The canonical as the pose alone would place it: what a fold or a stretch is judged against.
  const Eigen::Matrix4d& T = result.fits[active_spaces(result).front()].T_observed_canonical;
  const Points posed = ((model.canonical_mesh.vertices * model.observed_diagonal()) *
                        nearest_rotation(T.topLeftCorner<3, 3>()).transpose())
                           .rowwise() +
                       T.topRightCorner<3, 1>().transpose();
  mesh.vertices = detail::relax_faults(mesh.faces, posed, moved, detail::MeshFaults{});
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

std::vector<Region> frame_regions(const CategoryModel& model, const std::vector<Points>& anchor_sets,
                                  double radius) {
  if (!(radius > 0.0)) throw UsageError("a frame's region radius must be positive");
  const KdTree tree(model.canonical);
  std::vector<Region> regions;
  for (const Points& anchor_set : anchor_sets) {
    const Points anchors = model.normalization.apply(anchor_set);
    std::map<int, double> nearest;  // row -> squared distance to the nearest anchor
    std::vector<std::pair<int, double>> near;
    for (Eigen::Index a = 0; a < anchors.rows(); ++a) {
      const Eigen::Vector3d anchor = anchors.row(a).transpose();
      tree.radius(anchor, 3.0 * radius, near);
      for (const auto& entry : tree.nearest_k(anchor, kMinimumRegionPoints)) near.push_back(entry);
      for (const auto& [row, squared] : near) {
        const auto found = nearest.find(row);
        if (found == nearest.end() || squared < found->second) nearest[row] = squared;
      }
    }
    Region region;
    region.weights.resize(static_cast<Eigen::Index>(nearest.size()));
    for (const auto& [row, squared] : nearest) {
      region.weights[static_cast<Eigen::Index>(region.rows.size())] = std::exp(-squared / (2.0 * radius * radius));
      region.rows.push_back(row);
    }
    regions.push_back(std::move(region));
  }
  return regions;
}

Eigen::Matrix3d region_motion(const Points& before, const Points& after, const Eigen::VectorXd& weights,
                              const Eigen::Matrix3d& free_axes_rotation) {
  const auto centred = [&](const Points& points) -> Points {
    const Eigen::RowVector3d mean = (weights.asDiagonal() * points).colwise().sum() / weights.sum();
    return points.rowwise() - mean;
  };
  // max tr(R^T M) with M = sum w q p^T is the Kabsch rotation; a small share of another rotation in M
  // decides the axes the region leaves free (a straight bar's own axis) and nothing else.
  Eigen::Matrix3d cross = centred(after).transpose() * weights.asDiagonal() * centred(before);
  cross += kPosePrior * cross.norm() * free_axes_rotation;
  return nearest_rotation(cross);
}

std::vector<Eigen::Matrix3d> region_rotations(const CategoryModel& model, const RegistrationResult& result,
                                              const std::vector<Points>& anchor_sets, double radius) {
  const std::vector<std::size_t> spaces = active_spaces(result);
  const std::vector<Region> regions = frame_regions(model, anchor_sets, radius);
  std::vector<int> all_rows;  // every region moves in one deform_points
  for (const Region& region : regions) all_rows.insert(all_rows.end(), region.rows.begin(), region.rows.end());
  const Points before = model.normalization.undo(select_rows(model.canonical, all_rows));
  const Points after = deform_points(model, result, before, {}, Follow::material);
  const Eigen::Matrix3d pose_rotation =
      nearest_rotation(result.fits[spaces.front()].T_observed_canonical.topLeftCorner<3, 3>());
  std::vector<Eigen::Matrix3d> rotations;
  Eigen::Index offset = 0;
  for (const Region& region : regions) {
    const auto count = static_cast<Eigen::Index>(region.rows.size());
    rotations.push_back(region_motion(before.middleRows(offset, count), after.middleRows(offset, count),
                                      region.weights, pose_rotation));
    offset += count;
  }
  return rotations;
}

std::vector<Frame> transfer_frames(const CategoryModel& model, const RegistrationResult& result,
                                   const std::vector<Frame>& frames, double radius) {
  if (frames.empty()) return {};
  Points positions(static_cast<Eigen::Index>(frames.size()), 3);
  for (std::size_t f = 0; f < frames.size(); ++f) positions.row(static_cast<Eigen::Index>(f)) = frames[f].position.transpose();
  const Points carried = deform_points(model, result, positions, {}, Follow::material);
  std::vector<Frame> moved = frames;
  for (std::size_t f = 0; f < frames.size(); ++f) moved[f].position = carried.row(static_cast<Eigen::Index>(f)).transpose();
  std::vector<Points> anchors;
  for (const Frame& frame : frames) anchors.push_back(frame.position.transpose());
  const std::vector<Eigen::Matrix3d> turns = region_rotations(model, result, anchors, radius);
  for (std::size_t f = 0; f < frames.size(); ++f) moved[f].rotation = turns[f] * frames[f].rotation;
  return moved;
}

}  // namespace partreg::core
