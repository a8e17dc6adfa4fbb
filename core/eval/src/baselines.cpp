#include "partreg/eval/baselines.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"
#include "partreg/core/geometry/sampling.hpp"

namespace partreg::eval {
namespace {

// `points` farthest-point sampled to `count` (all of them when there are no more), as the canonical was.
core::Points sampled_to(const core::Points& points, std::size_t count) {
  return core::select_rows(points, core::subsample_indices(points, count, /*voxel_size=*/0.0));
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Every k-th observed point, at most `count`: a rigid fit needs few, and striding keeps them spread.
core::Points strided(const core::Points& points, int count) {
  if (points.rows() <= count) return points;
  std::vector<int> rows;
  for (int i = 0; i < count; ++i) rows.push_back(static_cast<int>(points.rows() * i / count));
  return core::select_rows(points, rows);
}

core::Points transformed(const core::Points& points, const Eigen::Matrix4d& T) {
  return (points * T.topLeftCorner<3, 3>().transpose()).rowwise() + T.topRightCorner<3, 1>().transpose();
}

// The squared distance below which the closest `fraction` of the pairs lie (at least 3 pairs are kept).
double kept_threshold(const Eigen::VectorXd& squared, double fraction) {
  std::vector<double> sorted(squared.data(), squared.data() + squared.size());
  const std::size_t kept = std::min(
      sorted.size(), std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(fraction * sorted.size()))));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(kept - 1), sorted.end());
  return sorted[kept - 1];
}

// ICP from one start, solving T_template_observed (the observation moves onto the fixed template tree).
RigidAlignment align_from(const core::KdTree& tree, const core::Points& observed,
                          const Eigen::Matrix3d& R_observed_template, const IcpSettings& settings) {
  const Eigen::Vector3d observed_centroid = observed.colwise().mean().transpose();
  const Eigen::Vector3d template_centroid = tree.points().colwise().mean().transpose();
  Eigen::Matrix4d T_template_observed = Eigen::Matrix4d::Identity();
  T_template_observed.topLeftCorner<3, 3>() = R_observed_template.transpose();
  T_template_observed.topRightCorner<3, 1>() =
      template_centroid - R_observed_template.transpose() * observed_centroid;
  RigidAlignment alignment;
  double previous = std::numeric_limits<double>::infinity();
  std::vector<int> nearest;
  Eigen::VectorXd squared;
  for (int step = 0; step < settings.max_iterations; ++step) {
    tree.nearest_all(transformed(observed, T_template_observed), nearest, squared);
    const double threshold = kept_threshold(squared, settings.kept_fraction);
    Eigen::Matrix3Xd from(3, observed.rows()), to(3, observed.rows());
    Eigen::Index pairs = 0;
    double sum = 0.0;
    for (Eigen::Index n = 0; n < observed.rows(); ++n)
      if (squared[n] <= threshold) {
        from.col(pairs) = observed.row(n).transpose();
        to.col(pairs) = tree.points().row(nearest[static_cast<std::size_t>(n)]).transpose();
        sum += squared[n], ++pairs;
      }
    alignment.rms = std::sqrt(sum / double(pairs));
    alignment.iterations = step + 1;
    if (std::isfinite(previous) && std::abs(previous - alignment.rms) <= settings.tolerance * previous) break;
    previous = alignment.rms;
    T_template_observed = Eigen::umeyama(from.leftCols(pairs), to.leftCols(pairs), false);
  }
  alignment.T_observed_template = T_template_observed.inverse();
  return alignment;
}

// The aligned template scored against the truth. `part` per template row (or empty).
core::TruthErrors score(const core::KdTree& shape, const Eigen::Matrix4d& T_observed_shape,
                        const Eigen::VectorXi& part, const std::vector<std::string>& part_names,
                        const BaselineObservation& observation, const core::Points* truth_of_row) {
  return core::measure_against_truth(transformed(shape.points(), T_observed_shape), part, part_names,
                                     *observation.truth, observation.diagonal, truth_of_row);
}

}  // namespace

std::vector<Eigen::Matrix3d> start_rotations(int restarts, const Eigen::Vector3d& up) {
  std::vector<Eigen::Matrix3d> starts;
  const int count = std::max(1, restarts);
  for (int k = 0; k < count; ++k)
    starts.push_back(Eigen::AngleAxisd(2.0 * M_PI * k / count, up.normalized()).toRotationMatrix());
  return starts;
}

RigidAlignment align_rigidly(const core::KdTree& template_tree, const core::Points& observed,
                             const std::vector<Eigen::Matrix3d>& starts, const IcpSettings& settings) {
  if (observed.rows() < 3 || template_tree.size() < 3)
    throw InputError("a rigid alignment needs at least 3 observed and 3 template points");
  if (starts.empty()) throw InputError("a rigid alignment needs at least one start rotation");
  const core::Points used = strided(observed, settings.max_points);
  RigidAlignment best;
  best.rms = std::numeric_limits<double>::infinity();
  for (const Eigen::Matrix3d& start : starts) {
    RigidAlignment candidate = align_from(template_tree, used, start, settings);
    if (candidate.rms < best.rms) best = candidate;
  }
  return best;
}

std::vector<Template> fold_templates(const core::CategoryModel& model,
                                     const std::vector<core::TrainingInstance>& training) {
  std::vector<Template> templates;
  templates.push_back(
      {model.training.canonical, core::KdTree(model.normalization.undo(model.canonical)), true});
  const std::size_t count = static_cast<std::size_t>(model.canonical.rows());
  for (const core::TrainingInstance& instance : training) {
    const auto& names = model.training.instances;
    if (instance.name == model.training.canonical ||
        std::find(names.begin(), names.end(), instance.name) == names.end())
      continue;
    templates.push_back({instance.name, core::KdTree(sampled_to(instance.points, count)), false});
  }
  return templates;
}

std::vector<Template> model_templates(const core::CategoryModel& model) {
  std::vector<Template> templates;
  templates.push_back(
      {model.training.canonical, core::KdTree(model.normalization.undo(model.canonical)), true});
  const core::ShapeSpace& holistic = model.holistic();
  for (std::size_t i = 0; i < model.training.instances.size(); ++i) {
    if (model.training.instances[i] == model.training.canonical) continue;
    const core::Points weights = model.training_weight_field(static_cast<int>(i));
    const core::Points fitted =
        holistic.canonical +
        core::Points(core::apply_kernel(holistic.canonical, holistic.canonical, weights, holistic.beta));
    templates.push_back({model.training.instances[i], core::KdTree(model.normalization.undo(fitted)), false});
  }
  return templates;
}

core::Points mean_shape(const core::CategoryModel& model) {
  const core::ShapeSpace& holistic = model.holistic();
  return model.normalization.undo(holistic.deformed(Eigen::VectorXd::Zero(holistic.dimensions())));
}

core::Points true_shape_points(const core::CategoryModel& model, const core::Points& surface) {
  return sampled_to(surface, static_cast<std::size_t>(model.canonical.rows()));
}

std::vector<BaselineScore> score_baselines(const core::CategoryModel& model,
                                           const std::vector<Template>& templates,
                                           const BaselineObservation& observation,
                                           const std::vector<Eigen::Matrix3d>& starts,
                                           const IcpSettings& icp) {
  if (templates.empty()) throw InputError("the baselines need at least one template");
  if (!observation.observed || !observation.truth) throw InputError("the baselines need an observation");
  BaselineScore oracle{Baseline::oracle_template, {}, "", 0.0},
      canonical{Baseline::rigid_canonical, {}, "", 0.0};
  oracle.errors.symmetric_rms_per_diagonal = std::numeric_limits<double>::infinity();
  const auto oracle_start = Clock::now();
  for (const Template& shape : templates) {
    const auto start = Clock::now();
    const RigidAlignment alignment = align_rigidly(shape.tree, *observation.observed, starts, icp);
    // Only the canonical has the canonical's rows: its parts and correspondences are meaningful.
    const core::TruthErrors errors =
        shape.is_canonical ? score(shape.tree, alignment.T_observed_template, model.canonical_part,
                                   model.part_names, observation, observation.truth_of_canonical_row)
                           : score(shape.tree, alignment.T_observed_template, {}, {}, observation, nullptr);
    if (shape.is_canonical)
      canonical = {Baseline::rigid_canonical, errors, shape.name, seconds_since(start),
                   alignment.T_observed_template};
    if (errors.symmetric_rms_per_diagonal < oracle.errors.symmetric_rms_per_diagonal)
      oracle.errors = errors, oracle.shape = shape.name;
  }
  // Other templates have no canonical rows: the oracle's row keeps only what every template has.
  oracle.errors.part_eq5_per_diagonal2.clear();
  oracle.errors.correspondence_per_diagonal.reset();
  oracle.seconds = seconds_since(oracle_start);
  const auto mean_start = Clock::now();
  const core::Points mean_posed = transformed(mean_shape(model), observation.T_observed_canonical);
  BaselineScore mean{
      Baseline::mean_shape,
      core::measure_against_truth(mean_posed, model.canonical_part, model.part_names, *observation.truth,
                                  observation.diagonal, observation.truth_of_canonical_row),
      "mean", 0.0};
  mean.seconds = seconds_since(mean_start);
  if (!observation.true_shape) return {oracle, canonical, mean};
  const auto true_start = Clock::now();
  BaselineScore truth{Baseline::true_shape,
                      core::measure_against_truth(*observation.true_shape, {}, {}, *observation.truth,
                                                  observation.diagonal, nullptr),
                      "tested", 0.0};
  truth.seconds = seconds_since(true_start);
  return {oracle, canonical, mean, truth};
}

}  // namespace partreg::eval
