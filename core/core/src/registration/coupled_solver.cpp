#include "coupled_solver.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>

#include "mixture_fit.hpp"
#include "moment_cost.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"

namespace partreg::core::detail {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The effective pose of a part, [quaternion (x, y, z, w) ; translation], from the object's pose and the
// part's offset (see the header). Templated so that Ceres differentiates it exactly.
struct OffsetPose {
  Eigen::Vector3d centre;  // the part's canonical centroid c_p, the offset's pivot

  template <typename T>
  bool operator()(const T* object_rotation, const T* object_translation, const T* scale,
                  const T* offset_rotation, const T* offset_translation, T* out) const {
    using Vector = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Eigen::Quaternion<T>> object(object_rotation);
    T wxyz[4];
    ceres::AngleAxisToQuaternion(offset_rotation, wxyz);
    const Eigen::Quaternion<T> offset(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    Eigen::Map<Eigen::Quaternion<T>> combined(out);
    combined = object * offset;
    const Vector c = centre.cast<T>();
    const Vector moved_pivot =
        c + Eigen::Map<const Vector>(offset_translation) - offset.toRotationMatrix() * c;
    Eigen::Map<Vector>(out + 4) =
        scale[0] * (object.toRotationMatrix() * moved_pivot) + Eigen::Map<const Vector>(object_translation);
    return true;
  }
};
using OffsetPoseCost = ceres::AutoDiffCostFunction<OffsetPose, 7, 4, 3, 1, 3, 3>;

// One part's data term: its space's MomentCost at the part's effective pose, chained to the object's pose
// and the offset. Parameter blocks: object rotation (4), translation (3), scale (1), offset rotation
// (angle-axis, 3), offset translation (3), latent (q).
class OffsetPartCost : public ceres::CostFunction {
 public:
  OffsetPartCost(const ShapeSpace& space, const std::vector<WeightedPair>& pairs, double prior_weight,
                 const Eigen::Vector3d& centre)
      : moment_(space, pairs, prior_weight), pose_(new OffsetPose{centre}) {
    set_num_residuals(moment_.num_residuals());
    *mutable_parameter_block_sizes() = {4, 3, 1, 3, 3, space.dimensions()};
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    static constexpr int kSizes[5] = {4, 3, 1, 3, 3};
    double effective[7], d_rotation[28], d_translation[21], d_scale[7], d_offset_rotation[21],
        d_offset_translation[21];
    double* pose_jacobians[5] = {d_rotation, d_translation, d_scale, d_offset_rotation, d_offset_translation};
    if (!pose_.Evaluate(parameters, effective, jacobians ? pose_jacobians : nullptr)) return false;
    const double* inner[4] = {effective, effective + 4, parameters[2], parameters[5]};
    if (!jacobians) return moment_.Evaluate(inner, residuals, nullptr);
    const int rows = num_residuals();
    RowMajor by_pose(rows, 7), by_scale(rows, 1);
    RowMajor by_translation(rows, 3);
    RowMajor by_rotation(rows, 4);
    double* inner_jacobians[4] = {by_rotation.data(), by_translation.data(), by_scale.data(), jacobians[5]};
    if (!moment_.Evaluate(inner, residuals, inner_jacobians)) return false;
    by_pose << by_rotation, by_translation;
    for (int b = 0; b < 5; ++b) {
      if (!jacobians[b]) continue;
      Eigen::Map<RowMajor> J(jacobians[b], rows, kSizes[b]);
      J = by_pose * Eigen::Map<const RowMajor>(pose_jacobians[b], 7, kSizes[b]);
      if (b == 2) J += by_scale;  // the scale also multiplies the deformed points directly
    }
    return true;
  }

 private:
  MomentCost moment_;
  OffsetPoseCost pose_;
};

// The prior on one part's offset: sqrt(offset_weight) (rho r, d).
struct OffsetPrior {
  double root_weight, radius;
  template <typename T>
  bool operator()(const T* rotation, const T* translation, T* out) const {
    for (int i = 0; i < 3; ++i) {
      out[i] = root_weight * radius * rotation[i];
      out[3 + i] = root_weight * translation[i];
    }
    return true;
  }
};

// One part's motion m_p(z) of given points z before the object pose, linear in the latent:
// m_p(z) = R_p (rest + basis x_p) + c_p + d_p with rest = z + G(z, C_p) W_mean - c_p.
struct SeamSide {
  Points rest;            // N x 3
  Eigen::MatrixXd basis;  // 3N x q, row 3 i + a: component a at point i per unit of each latent
  Eigen::Vector3d centre;
};

SeamSide seam_side(const ShapeSpace& space, const Points& z, const Eigen::Vector3d& centre) {
  const Eigen::MatrixXd G = gaussian_kernel(z, space.canonical, space.beta);
  const auto field = [&](const double* vectorised) {
    return Points(G * Eigen::Map<const Points>(vectorised, space.point_count(), 3));
  };
  SeamSide side;
  side.centre = centre;
  side.rest = (z + field(space.mean.data())).rowwise() - centre.transpose();
  side.basis.resize(3 * z.rows(), space.dimensions());
  for (int k = 0; k < space.dimensions(); ++k) {
    const Points moved = field(space.basis.col(k).data());
    side.basis.col(k) = Eigen::Map<const Eigen::VectorXd>(moved.data(), moved.size());  // row-major: 3 i + a
  }
  return side;
}

// An offset rotation R(r) (angle-axis r) and its derivative along each component of r, through Ceres's own
// conversion so that R matches the data term's offset pose.
struct Rotation {
  Eigen::Matrix3d matrix;
  std::array<Eigen::Matrix3d, 3> derivative;
  explicit Rotation(const double* angle_axis) {
    using Jet = ceres::Jet<double, 3>;
    const Jet r[3] = {Jet(angle_axis[0], 0), Jet(angle_axis[1], 1), Jet(angle_axis[2], 2)};
    Jet R[9];
    ceres::AngleAxisToRotationMatrix(r, ceres::RowMajorAdapter3x3(R));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        matrix(i, j) = R[3 * i + j].a;
        for (int k = 0; k < 3; ++k) derivative[static_cast<std::size_t>(k)](i, j) = R[3 * i + j].v[k];
      }
  }
};

// sqrt(seam_weight / all seam points) (m_a(z) - m_b(z)) at the seam points of one pair of parts, with exact
// derivatives (the motion is linear in the latent and the translation; the rotation's derivative comes once
// per evaluation from Rotation). Parameter blocks: part a's offset rotation, translation and latent, then
// part b's.
class SeamCost : public ceres::CostFunction {
 public:
  SeamCost(std::shared_ptr<const SeamSide> a, std::shared_ptr<const SeamSide> b, double root_weight)
      : a_(std::move(a)), b_(std::move(b)), root_weight_(root_weight) {
    for (const SeamSide* side : {a_.get(), b_.get()})
      for (const auto size : {Eigen::Index{3}, Eigen::Index{3}, side->basis.cols()})
        mutable_parameter_block_sizes()->push_back(static_cast<int>(size));
    set_num_residuals(static_cast<int>(3 * a_->rest.rows()));
  }

  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override {
    const Eigen::Index n = a_->rest.rows();
    Eigen::Map<Eigen::VectorXd> r(residuals, 3 * n);
    r.setZero();
    const SeamSide* sides[2] = {a_.get(), b_.get()};
    for (int s = 0; s < 2; ++s) {
      const SeamSide& side = *sides[s];
      const double sign = s == 0 ? root_weight_ : -root_weight_;
      const Rotation rotation(p[3 * s]);
      const Eigen::Map<const Eigen::Vector3d> translation(p[3 * s + 1]);
      const Eigen::Map<const Eigen::VectorXd> latent(p[3 * s + 2], side.basis.cols());
      double* const* J = jacobians ? jacobians + 3 * s : nullptr;
      for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Vector3d v = side.rest.row(i).transpose() + side.basis.middleRows<3>(3 * i) * latent;
        r.segment<3>(3 * i) += sign * (rotation.matrix * v + side.centre + translation);
        if (!J) continue;
        if (J[0]) {
          Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> block(J[0], 3 * n, 3);
          for (int k = 0; k < 3; ++k)
            block.block<3, 1>(3 * i, k) = sign * rotation.derivative[static_cast<std::size_t>(k)] * v;
        }
        if (J[1]) {
          Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> block(J[1], 3 * n, 3);
          block.block<3, 3>(3 * i, 0) = sign * Eigen::Matrix3d::Identity();
        }
        if (J[2]) {
          Eigen::Map<RowMajor> block(J[2], 3 * n, side.basis.cols());
          block.middleRows<3>(3 * i) = sign * rotation.matrix * side.basis.middleRows<3>(3 * i);
        }
      }
    }
    return true;
  }

 private:
  std::shared_ptr<const SeamSide> a_, b_;
  double root_weight_;
};

// What the solver knows about each part space.
struct Part {
  const ShapeSpace* space;
  Eigen::Vector3d centre;  // canonical centroid (normalised)
  double radius;           // RMS distance of the canonical points from it
  ViewSurface surface;     // of the space's canonical points; empty without a viewpoint
};

// The canonical points of part `a` within `radius` of part `b`'s, and those of `b` within it of `a`'s.
Points seam_points(const ShapeSpace& a, const ShapeSpace& b, double radius) {
  std::vector<Eigen::RowVector3d> found;
  for (const auto& [own, other] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
    const KdTree tree(other->canonical);
    for (Eigen::Index i = 0; i < own->canonical.rows(); ++i)
      if (tree.nearest(own->canonical.row(i).transpose()).second <= radius * radius)
        found.push_back(own->canonical.row(i));
  }
  Points points(static_cast<Eigen::Index>(found.size()), 3);
  for (std::size_t i = 0; i < found.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = found[i];
  return points;
}

// The seam points of two parts and each part's motion of them, computed once per registration.
struct Seam {
  int a, b;  // indices into the parts
  std::shared_ptr<const SeamSide> on_a, on_b;
};

std::vector<Seam> find_seams(const std::vector<Part>& parts, double radius) {
  std::vector<Seam> seams;
  for (std::size_t a = 0; a < parts.size(); ++a)
    for (std::size_t b = a + 1; b < parts.size(); ++b) {
      const Points points = seam_points(*parts[a].space, *parts[b].space, radius);
      if (points.rows() == 0) continue;
      seams.push_back(
          {static_cast<int>(a), static_cast<int>(b),
           std::make_shared<const SeamSide>(seam_side(*parts[a].space, points, parts[a].centre)),
           std::make_shared<const SeamSide>(seam_side(*parts[b].space, points, parts[b].centre))});
    }
  return seams;
}

// Everything the joint problem solves for.
struct Unknowns {
  Pose object;
  std::vector<Eigen::Vector3d> offset_rotation, offset_translation;  // angle-axis (rad), normalised length
  std::vector<Eigen::VectorXd> latent;

  Pose part_pose(const Part& part, std::size_t p) const {
    double effective[7];
    OffsetPose{part.centre}(object.rotation.coeffs().data(), object.translation.data(), &object.scale,
                            offset_rotation[p].data(), offset_translation[p].data(), effective);
    Pose pose;
    pose.rotation = Eigen::Quaterniond(effective[3], effective[0], effective[1], effective[2]);
    pose.translation = Eigen::Vector3d(effective[4], effective[5], effective[6]);
    pose.scale = object.scale;
    return pose;
  }

  // How far everything moved since `before` (radians and normalised lengths, latents in their own units).
  double distance_to(const Unknowns& before) const {
    double moved = (object.translation - before.object.translation).norm() +
                   object.rotation.angularDistance(before.object.rotation);
    for (std::size_t p = 0; p < latent.size(); ++p)
      moved += (latent[p] - before.latent[p]).norm() +
               (offset_rotation[p] - before.offset_rotation[p]).norm() +
               (offset_translation[p] - before.offset_translation[p]).norm();
    return moved;
  }
};

// The object's posed deformed canonical points in holistic row order, and which the viewpoint sees (each
// part's normals under its own pose; the whole object occludes, `spacing` the holistic points').
Points assemble(const CategoryModel& model, const std::vector<Part>& parts, const Unknowns& unknowns,
                const Observation& observation, double spacing, std::vector<bool>& visible) {
  Points posed(model.canonical.rows(), 3);
  visible.assign(static_cast<std::size_t>(model.canonical.rows()), true);
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const Pose pose = unknowns.part_pose(parts[p], p);
    const Points own = pose.apply(parts[p].space->deformed(unknowns.latent[p]));
    const std::vector<bool> own_visible = facing_rows(own, parts[p].surface, pose, observation.viewpoint);
    const std::vector<int>& rows = parts[p].space->point_indices;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      posed.row(rows[i]) = own.row(static_cast<Eigen::Index>(i));
      visible[static_cast<std::size_t>(rows[i])] = own_visible[i];
    }
  }
  if (observation.viewpoint && !parts.empty() && parts.front().surface.normals.rows() > 0)
    visible = seen_rows(posed, visible, *observation.viewpoint, spacing);
  return posed;
}

// The step's weighted pairs of the whole object, handed to the parts (rows become each space's own rows).
std::vector<std::vector<WeightedPair>> pairs_by_part(const CategoryModel& model,
                                                     const std::vector<WeightedPair>& pairs) {
  std::vector<int> own_row(static_cast<std::size_t>(model.canonical.rows()), 0);
  for (std::size_t s = 1; s < model.spaces.size(); ++s)
    for (std::size_t i = 0; i < model.spaces[s].point_indices.size(); ++i)
      own_row[static_cast<std::size_t>(model.spaces[s].point_indices[i])] = static_cast<int>(i);
  std::vector<std::vector<WeightedPair>> by_part(model.spaces.size() - 1);
  for (const WeightedPair& pair : pairs) {
    WeightedPair own = pair;
    own.row = own_row[static_cast<std::size_t>(pair.row)];
    by_part[static_cast<std::size_t>(model.canonical_part[pair.row])].push_back(own);
  }
  return by_part;
}

std::vector<Part> describe_parts(const CategoryModel& model, const ViewSurface& surface) {
  std::vector<Part> parts;
  for (std::size_t s = 1; s < model.spaces.size(); ++s) {
    const ShapeSpace& space = model.spaces[s];
    const Eigen::Vector3d centre = space.canonical.colwise().mean().transpose();
    const double radius =
        std::sqrt((space.canonical.rowwise() - centre.transpose()).rowwise().squaredNorm().mean());
    // Only the part's normals are used (facing_rows): the whole object occludes, at the whole's spacing.
    const ViewSurface own = surface.normals.rows()
                                ? ViewSurface{select_rows(surface.normals, space.point_indices), surface.spacing}
                                : ViewSurface();
    parts.push_back({&space, centre, radius, own});
  }
  return parts;
}

// Adds the seam terms; their parameter blocks are the offsets and latents in `unknowns`.
void add_seams(ceres::Problem& problem, const std::vector<Seam>& seams, Unknowns& unknowns,
               double seam_weight) {
  Eigen::Index total = 0;
  for (const Seam& seam : seams) total += seam.on_a->rest.rows();
  if (total == 0 || seam_weight <= 0.0) return;
  for (const Seam& seam : seams) {
    std::vector<double*> blocks;
    for (const int p : {seam.a, seam.b}) {
      const auto index = static_cast<std::size_t>(p);
      for (double* block : {unknowns.offset_rotation[index].data(), unknowns.offset_translation[index].data(),
                            unknowns.latent[index].data()})
        blocks.push_back(block);
    }
    problem.AddResidualBlock(
        new SeamCost(seam.on_a, seam.on_b, std::sqrt(seam_weight / static_cast<double>(total))), nullptr,
        blocks);
  }
}

// One outer step's problem: the data term of every part at the step's pairs, the priors and the seams.
// `prior_weight`: the latents' (the settings' own, or grown with a mixture's noise: noisy_prior_weight),
// shared out to the parts by their data (part_prior_weights).
double solve_step(const std::vector<Part>& parts, const std::vector<Seam>& seams,
                  const std::vector<std::vector<WeightedPair>>& pairs, Unknowns& unknowns,
                  const RegistrationSettings& settings, double prior_weight) {
  ceres::Problem problem;
  double* rotation = unknowns.object.rotation.coeffs().data();
  double* translation = unknowns.object.translation.data();
  double* scale = &unknowns.object.scale;
  const std::vector<double> part_priors = part_prior_weights(pairs, prior_weight);
  for (std::size_t p = 0; p < parts.size(); ++p) {
    problem.AddResidualBlock(new OffsetPartCost(*parts[p].space, pairs[p], part_priors[p], parts[p].centre),
                             nullptr,
                             {rotation, translation, scale, unknowns.offset_rotation[p].data(),
                              unknowns.offset_translation[p].data(), unknowns.latent[p].data()});
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OffsetPrior, 6, 3, 3>(new OffsetPrior{
                                 std::sqrt(settings.objective.offset_weight), parts[p].radius}),
                             nullptr, unknowns.offset_rotation[p].data(),
                             unknowns.offset_translation[p].data());
  }
  add_seams(problem, seams, unknowns, settings.objective.seam_weight.value());  // with_model_defaults set it
  constrain_pose(problem, rotation, scale, settings);
  return solve_inner(problem, settings);  // 7 + P (6 + q) unknowns
}

Unknowns start_from(const CategoryModel& model, const SpaceSolution& holistic) {
  const ShapeSpace& whole = model.holistic();
  const Points displacement = whole.deformed(holistic.latent) - whole.canonical;
  Unknowns unknowns;
  unknowns.object = holistic.pose;
  for (std::size_t s = 1; s < model.spaces.size(); ++s) {
    const ShapeSpace& space = model.spaces[s];
    unknowns.latent.push_back(space.project_displacement(select_rows(displacement, space.point_indices)));
    unknowns.offset_rotation.push_back(Eigen::Vector3d::Zero());
    unknowns.offset_translation.push_back(Eigen::Vector3d::Zero());
  }
  return unknowns;
}

}  // namespace

std::vector<double> part_prior_weights(const std::vector<std::vector<WeightedPair>>& pairs,
                                       double prior_weight) {
  std::vector<double> data(pairs.size(), 0.0);
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (const WeightedPair& pair : pairs[p]) data[p] += pair.weight;
  const double total = std::accumulate(data.begin(), data.end(), 0.0);
  std::vector<double> weights(pairs.size(), prior_weight);
  if (total > 0.0)
    for (std::size_t p = 0; p < pairs.size(); ++p) weights[p] = prior_weight * data[p] / total;
  return weights;
}

std::unique_ptr<ceres::CostFunction> make_part_data_cost(const ShapeSpace& space,
                                                         const std::vector<WeightedPair>& pairs,
                                                         double prior_weight, const Eigen::Vector3d& centre) {
  return std::make_unique<OffsetPartCost>(space, pairs, prior_weight, centre);
}

std::unique_ptr<ceres::CostFunction> make_seam_cost(const ShapeSpace& a, const Eigen::Vector3d& centre_a,
                                                    const ShapeSpace& b, const Eigen::Vector3d& centre_b,
                                                    const Points& z, double root_weight) {
  return std::make_unique<SeamCost>(std::make_shared<const SeamSide>(seam_side(a, z, centre_a)),
                                    std::make_shared<const SeamSide>(seam_side(b, z, centre_b)), root_weight);
}

std::vector<SearchOutcome> solve_coupled(const CategoryModel& model, const ViewSurface& surface,
                                         const Observation& observation, const SpaceSolution& holistic,
                                         const RegistrationSettings& settings, const Points* mixture_targets,
                                         const std::vector<bool>& centres) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Part> parts = describe_parts(model, surface);
  const std::vector<Seam> seams = find_seams(parts, settings.objective.seam_radius);
  Unknowns unknowns = start_from(model, holistic);
  std::vector<SearchOutcome> outcomes(parts.size());
  for (SearchOutcome& outcome : outcomes) {
    outcome.hypotheses = 1;
    outcome.runner_up = std::numeric_limits<double>::infinity();
    outcome.best_start = holistic.pose;
  }
  double previous = std::numeric_limits<double>::infinity();
  bool converged = false, had_pairs = true;
  int iterations = 0;
  double cost = 0.0;
  CorrespondenceHints hints;
  // Each step's latents and poses, per part, for the registration's history.
  const auto record_step = [&] {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (std::size_t p = 0; p < parts.size(); ++p) {
      SpaceSolution& solution = outcomes[p].best;
      solution.steps.emplace_back(unknowns.latent[p], unknowns.part_pose(parts[p], p));
      solution.step_costs.push_back(cost);
      solution.step_seconds.push_back(seconds);
    }
  };
  for (int outer = 0; outer < settings.convergence.outer_iterations; ++outer) {
    std::vector<bool> visible;
    const Points posed = assemble(model, parts, unknowns, observation, surface.spacing, visible);
    const Correspondences pairs = correspond(posed, visible, observation, settings, &hints);
    if (pairs.from_canonical.empty() && pairs.from_observed.empty()) {
      had_pairs = false;
      break;
    }
    const Unknowns before = unknowns;
    cost =
        solve_step(parts, seams, pairs_by_part(model, weighted_pairs(pairs, settings)), unknowns, settings,
                   settings.objective.prior_weight);
    iterations = outer + 1;
    record_step();
    // Settled as a single space's fit is: the cost or the unknowns stop moving.
    if (std::abs(previous - cost) <= settings.convergence.tolerance * std::max(cost, 1e-12) ||
        unknowns.distance_to(before) < settings.convergence.tolerance) {
      converged = true;
      break;
    }
    previous = cost;
  }
  if (mixture_targets && had_pairs) {
    // The same joint problem with the mixture's pairs in place of the closest points (mixture_fit.hpp).
    Mixture mixture(*mixture_targets, centres);
    for (int step = 0; step < settings.convergence.outer_iterations; ++step) {
      std::vector<bool> visible;
      const Points posed = assemble(model, parts, unknowns, observation, surface.spacing, visible);
      const std::vector<WeightedPair> pairs = mixture.pairs(posed, visible);
      if (pairs.empty()) break;
      cost = solve_step(parts, seams, pairs_by_part(model, pairs), unknowns, settings,
                        noisy_prior_weight(mixture.sigma(), settings.objective));
      ++iterations;
      record_step();
      if (mixture.update(assemble(model, parts, unknowns, observation, surface.spacing, visible), settings.convergence.tolerance))
        break;
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (std::size_t p = 0; p < parts.size(); ++p) {
    SpaceSolution& solution = outcomes[p].best;
    solution.latent = unknowns.latent[p];
    solution.pose = unknowns.part_pose(parts[p], p);
    solution.cost = cost;
    solution.iterations = iterations;
    solution.converged = converged;
    solution.had_pairs = had_pairs;
    solution.seconds = seconds;
  }
  return outcomes;
}

}  // namespace partreg::core::detail
