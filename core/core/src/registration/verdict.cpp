#include "partreg/core/registration/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/free_space.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "geometry/point_normals.hpp"

namespace partreg::core {
namespace {

// Surface samples of the deformed canonical mesh: enough that their spacing (about 0.01 of the diagonal on
// a mug) lies well under the inlier distance.
constexpr std::size_t kSurfaceSamples = 20000;

// The deformed model as points with unit normals, in the observation's units.
struct Surface {
  Points points, normals;
  double spacing = 0.0;  ///< median distance between neighbouring points: a point-to-plane figure's reach
};

// Samples drawn on the canonical mesh, carried onto the deformed one by their barycentric coordinates, so
// the samples follow the deformation exactly as the mesh's triangles do.
Surface mesh_surface(const CategoryModel& model, const RegistrationResult& result) {
  const Mesh deformed = deform_mesh(model, result);
  Eigen::VectorXi face;
  const Cloud samples = sample_surface(model.canonical_mesh, kSurfaceSamples, /*seed=*/7, &face);
  Surface surface;
  surface.points.resize(samples.points.rows(), 3);
  surface.normals.resize(samples.points.rows(), 3);
  for (Eigen::Index i = 0; i < samples.points.rows(); ++i) {
    const Eigen::Vector3i f = model.canonical_mesh.faces.row(face(i)).transpose();
    const Eigen::Vector3d a = model.canonical_mesh.vertices.row(f(0)), b = model.canonical_mesh.vertices.row(f(1)),
                          c = model.canonical_mesh.vertices.row(f(2));
    const Eigen::Vector3d p = samples.points.row(i);
    const Eigen::Vector3d u = b - a, v = c - a, w = p - a;
    const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), det = uu * vv - uv * uv;
    const double s = det > 0.0 ? (vv * u.dot(w) - uv * v.dot(w)) / det : 0.0;
    const double t = det > 0.0 ? (uu * v.dot(w) - uv * u.dot(w)) / det : 0.0;
    const Eigen::Vector3d A = deformed.vertices.row(f(0)), B = deformed.vertices.row(f(1)),
                          C = deformed.vertices.row(f(2));
    surface.points.row(i) = (A + s * (B - A) + t * (C - A)).transpose();
    const Eigen::Vector3d n = (B - A).cross(C - A);
    surface.normals.row(i) = n.norm() > 0.0 ? Eigen::RowVector3d(n.normalized().transpose()) : Eigen::RowVector3d::Zero();
  }
  return surface;
}

// A model trained on clouds: its deformed canonical points, normals from their neighbourhoods.
Surface point_surface(const RegistrationResult& result, double diagonal) {
  Surface surface;
  surface.points = result.deformed;
  surface.normals = detail::outward_normals(result.deformed, 0.05 * diagonal);
  return surface;
}

double median_spacing(const Points& points) {
  const KdTree tree(points);
  std::vector<double> spacing;
  for (Eigen::Index i = 0; i < points.rows(); i += std::max<Eigen::Index>(1, points.rows() / 500)) {
    const auto near = tree.nearest_k(points.row(i).transpose(), 2);
    if (near.size() == 2) spacing.push_back(std::sqrt(near[1].second));
  }
  if (spacing.empty()) return 0.0;
  std::nth_element(spacing.begin(), spacing.begin() + static_cast<long>(spacing.size() / 2), spacing.end());
  return spacing[spacing.size() / 2];
}

// Distance of each observed point to the surface: to the nearest sample's tangent plane within the samples'
// spacing of it, so the figure measures the surface rather than the gaps between its samples.
Eigen::VectorXd distances_to(const Surface& surface, const Points& observed) {
  const KdTree tree(surface.points);
  std::vector<int> index;
  Eigen::VectorXd squared;
  tree.nearest_all(observed, index, squared);
  Eigen::VectorXd distance(observed.rows());
  for (Eigen::Index i = 0; i < observed.rows(); ++i) {
    const Eigen::Vector3d offset = (observed.row(i) - surface.points.row(index[i])).transpose();
    const Eigen::Vector3d normal = surface.normals.row(index[i]).transpose();
    const double along = std::abs(offset.dot(normal));
    const double across = std::max(0.0, (offset - offset.dot(normal) * normal).norm() - surface.spacing);
    distance(i) = normal.squaredNorm() > 0.0 ? std::hypot(along, across) : offset.norm();
  }
  return distance;
}

double latent_distance_of(const RegistrationResult& result) {
  double largest = 0.0;
  for (const SpaceFit& fit : result.fits) largest = std::max(largest, fit.latent_distance);
  return largest;
}

// The whole object's pose search (the first fit: holistic where it ran): a distinct runner-up's score ratio.
double pose_ambiguity_of(const RegistrationResult& result, const VerdictSettings& settings) {
  if (result.fits.empty()) return std::numeric_limits<double>::infinity();
  const SpaceFit& fit = result.fits.front();
  if (!std::isfinite(fit.runner_up_score) || fit.runner_up_shift <= settings.distinct_pose || !(fit.score > 0.0))
    return std::numeric_limits<double>::infinity();
  return fit.runner_up_score / fit.score;
}

std::string number(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

std::string percent(double fraction) { return number(100.0 * fraction) + "%"; }

// Records a reason and raises the verdict to `level`.
void flag(Assessment& assessment, Verdict level, const std::string& reason) {
  assessment.verdict = std::max(assessment.verdict, level);
  assessment.reasons.push_back(std::string(level == Verdict::failed ? "failed: " : "doubtful: ") + reason);
}

}  // namespace

void validate(const VerdictSettings& s) {
  const auto share = [](double v) { return v >= 0.0 && v <= 1.0; };
  const auto length = [](double v) { return v >= 0.0 && std::isfinite(v); };
  if (!share(s.doubtful_inlier_share) || !share(s.failed_inlier_share) ||
      s.failed_inlier_share > s.doubtful_inlier_share)
    throw UsageError("verdict inlier shares must lie in [0, 1], the failed one below the doubtful one");
  if (!length(s.inlier_distance) || !length(s.noise_multiple) || !length(s.distinct_pose) || !length(s.doubtful_observed_rms) ||
      !length(s.failed_observed_rms) || !length(s.doubtful_seam_gap) || !length(s.failed_seam_gap) ||
      s.failed_observed_rms < s.doubtful_observed_rms || s.failed_seam_gap < s.doubtful_seam_gap)
    throw UsageError("verdict lengths must be finite and not negative, the failed ones above the doubtful ones");
  if (!share(s.doubtful_free_space_violation) || !share(s.failed_free_space_violation) ||
      s.failed_free_space_violation < s.doubtful_free_space_violation)
    throw UsageError("verdict free-space shares must lie in [0, 1], the failed one above the doubtful one");
  if (!length(s.doubtful_refinement_movement))
    throw UsageError("verdict: the refinement movement must be finite and not negative");
  if (!(s.doubtful_latent_distance > 0.0) || !(s.doubtful_pose_ambiguity >= 1.0) ||
      !(s.doubtful_mesh_stretch >= 1.0))
    throw UsageError("verdict: the latent distance must be positive, the pose ambiguity and stretch at least 1");
}

Assessment judge(const TrustFigures& f, const VerdictSettings& s) {
  validate(s);
  Assessment a;
  const std::string explained = "observed points within " + percent(s.inlier_distance) + " of the model: ";
  if (f.inlier_share < s.failed_inlier_share)
    flag(a, Verdict::failed, explained + percent(f.inlier_share) + " < " + percent(s.failed_inlier_share));
  else if (f.inlier_share < s.doubtful_inlier_share)
    flag(a, Verdict::doubtful, explained + percent(f.inlier_share) + " < " + percent(s.doubtful_inlier_share));
  // A figure past its failed threshold fails the result, past its doubtful one makes it doubtful; the reason
  // names the figure and the threshold it passed.
  const auto above = [&a](double value, double doubtful, double failed, const std::string& reason) {
    if (value > failed)
      flag(a, Verdict::failed, reason + percent(failed));
    else if (value > doubtful)
      flag(a, Verdict::doubtful, reason + percent(doubtful));
  };
  above(f.observed_rms, s.doubtful_observed_rms, s.failed_observed_rms,
        "observed-to-model RMS " + percent(f.observed_rms) + " of the diagonal > ");
  if (f.latent_distance > s.doubtful_latent_distance)
    flag(a, Verdict::doubtful,
         "shape unlike the training instances: latent " + number(f.latent_distance) + " sd from the mean > " +
             number(s.doubtful_latent_distance));
  if (f.refinement_movement > s.doubtful_refinement_movement)
    flag(a, Verdict::doubtful,
         "shape beyond the model's space: the refinement moved the fit by " + percent(f.refinement_movement) +
             " of the diagonal on average > " + percent(s.doubtful_refinement_movement));
  if (f.pose_ambiguity < s.doubtful_pose_ambiguity)
    flag(a, Verdict::doubtful,
         "ambiguous pose: a pose elsewhere scored within " + number(f.pose_ambiguity) + "x of the winner's");
  above(f.seam_gap_max, s.doubtful_seam_gap, s.failed_seam_gap,
        "parts apart: largest seam gap " + percent(f.seam_gap_max) + " of the diagonal > ");
  if (f.mesh_stretch > s.doubtful_mesh_stretch)
    flag(a, Verdict::doubtful,
         "mesh stretched: an edge " + number(f.mesh_stretch) + "x its canonical length > " +
             number(s.doubtful_mesh_stretch));
  if (f.free_space_violation)
    above(*f.free_space_violation, s.doubtful_free_space_violation, s.failed_free_space_violation,
          "model points where the camera saw free space: " + percent(*f.free_space_violation) + " > ");
  if (f.scale_at_bound)
    flag(a, Verdict::doubtful,
         "fitted scale " + number(f.scale) + " at its bound (scale-limit): check the units or the model's size");
  return a;
}

TrustFigures trust_figures(const CategoryModel& model, const Points& observed, const RegistrationResult& result,
                           const RegistrationSettings& settings) {
  TrustFigures f;
  const double diagonal = model.observed_diagonal();
  const Points sampled =
      select_rows(observed, subsample_indices(observed, static_cast<std::size_t>(settings.sampling.observed_points),
                                              settings.sampling.voxel_size * diagonal));
  // Left out: the points that stand alone, as registration leaves them (SamplingSettings::stray_limit):
  // uniform outliers are the sensor's, not the fit's; a table left in has company and counts. A point is
  // explained within the inlier distance or noise_multiple times the noise, whichever is farther: on the
  // evaluation's noisy views a correct fit read 40% inliers at 0.02 (drills, noise level 3).
  const Points measured =
      settings.sampling.stray_limit > 0.0
          ? select_rows(sampled, rows_with_neighbours(sampled, 2, settings.sampling.stray_limit))
          : sampled;
  Surface surface = model.canonical_mesh.faces.rows() > 0 ? mesh_surface(model, result)
                                                          : point_surface(result, diagonal);
  surface.spacing = median_spacing(surface.points);
  const Eigen::VectorXd distance = distances_to(surface, measured) / diagonal;
  const double noise = detail::observed_noise(Points(measured / diagonal), Points(result.deformed / diagonal));
  const double rms = std::sqrt(distance.squaredNorm() / static_cast<double>(distance.size()));
  f.observed_rms = std::sqrt(std::max(0.0, rms * rms - noise * noise));
  const double reach = std::max(settings.verdict.inlier_distance, settings.verdict.noise_multiple * noise);
  f.inlier_share = static_cast<double>((distance.array() <= reach).count()) / static_cast<double>(distance.size());
  f.latent_distance = latent_distance_of(result);
  f.refinement_movement = result.refinement.mean_movement;
  f.pose_ambiguity = pose_ambiguity_of(result, settings.verdict);
  const SeamGap gap = seam_gap(model, result);
  f.seam_gap_mean = gap.mean, f.seam_gap_max = gap.max;
  f.mesh_stretch = mesh_stretch(model, result);
  if (!result.fits.empty()) f.scale = result.fits.front().scale;
  const double limit = settings.objective.scale_limit;
  f.scale_at_bound = settings.objective.estimate_scale &&
                     (f.scale <= 1.0 / limit * (1.0 + 1e-3) || f.scale >= limit * (1.0 - 1e-3));
  // The deformed model's points, as registration scored them: the camera frame is the free space's to map.
  if (settings.free_space) f.free_space_violation = settings.free_space->violation_share(result.deformed);
  return f;
}

}  // namespace partreg::core
