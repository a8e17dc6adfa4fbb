#include "partreg/core/training/training.hpp"

#include <chrono>
#include <sstream>

#include "part_surfaces.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/training/training_options.hpp"
#include "space/seam_agreement.hpp"
#include "seam_weight_choice.hpp"

namespace partreg::core {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Points farthest_subset(const Points& points, int count) {
  const auto wanted = static_cast<std::size_t>(std::min<Eigen::Index>(count, points.rows()));
  return select_rows(points, farthest_point_indices(points, wanted));
}

double mean_nearest_distance(const Points& from, const Points& to) {
  const KdTree tree(to);
  std::vector<int> index;
  Eigen::VectorXd squared;
  tree.nearest_all(from, index, squared);
  return squared.cwiseSqrt().mean();
}

void check_instances(const std::vector<TrainingInstance>& instances,
                     const std::vector<std::string>& part_names) {
  if (instances.size() < 2)
    throw InputError("training needs at least two instances, got " + std::to_string(instances.size()));
  for (const TrainingInstance& instance : instances) {
    if (instance.points.rows() < 10)
      throw InputError("instance '" + instance.name + "' has only " + std::to_string(instance.points.rows()) +
                       " points");
    if (!instance.points.allFinite())
      throw InputError("instance '" + instance.name + "' has non-finite points");
    if (instance.part.size() == 0) continue;
    if (instance.part.size() != instance.points.rows())
      throw InputError("instance '" + instance.name + "': part labels do not match its points");
    if (instance.part.minCoeff() < 0 || instance.part.maxCoeff() >= static_cast<int>(part_names.size()))
      throw InputError("instance '" + instance.name + "' has a part label outside the category's parts");
  }
}

// Training's steps (CPDs and PCA-EMs), reported to the caller after each one.
using StepCounter = ProgressCounter;

struct CpdRun {
  Points weights;
  Points moved;
};

CpdRun register_onto(const Points& canonical, const Points& target, const TrainingSettings& settings,
                     const std::string& instance, const std::string& space, TrainingReport& report,
                     StepCounter& progress) {
  NonrigidCpdSettings cpd;
  cpd.beta = settings.beta;
  cpd.lambda = settings.lambda;
  cpd.outlier_weight = settings.outlier_weight;
  cpd.max_iterations = settings.max_iterations;
  cpd.normalize = false;  // the category is normalised once, so every W shares the same kernel G(C, C)
  const NonrigidCpdResult result = register_nonrigid(canonical, target, cpd);
  TrainingReport::Registration entry{instance, space, result.iterations, result.seconds,
                                     mean_nearest_distance(result.moved, target)};
  std::ostringstream line;
  if (progress.wanted())
    line << "cpd " << space << " -> " << instance << ": " << result.iterations << " iterations, "
         << result.seconds << " s, mean fit " << entry.mean_fit << " (normalised)";
  progress.step(line.str());
  report.registrations.push_back(entry);
  return {result.weights, result.moved};
}

}  // namespace

std::size_t choose_canonical(const std::vector<TrainingInstance>& instances, std::string* explanation) {
  std::vector<Points> samples;
  for (const TrainingInstance& instance : instances) samples.push_back(farthest_subset(instance.points, 500));
  const double diagonal = bounding_box_diagonal(instances.front().points);
  std::size_t best = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    double cost = 0.0;
    for (std::size_t j = 0; j < samples.size(); ++j)
      if (i != j)
        cost += mean_nearest_distance(samples[i], samples[j]) + mean_nearest_distance(samples[j], samples[i]);
    cost /= 2.0 * static_cast<double>(samples.size() - 1) * diagonal;
    if (cost < best_cost) best_cost = cost, best = i;
  }
  if (explanation) {
    std::ostringstream text;
    text << "medoid by symmetric Chamfer distance: '" << instances[best].name << "' is on average "
         << best_cost << " of a diagonal from the others";
    *explanation = text.str();
  }
  return best;
}

Eigen::VectorXi propagate_labels(const Points& labelled, const Eigen::VectorXi& labelled_part,
                                 const Points& points) {
  const KdTree tree(labelled);
  std::vector<int> index;
  Eigen::VectorXd squared;
  tree.nearest_all(points, index, squared);
  Eigen::VectorXi part(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    part[i] = labelled_part[index[static_cast<std::size_t>(i)]];
  return part;
}

namespace {

// An instance as CPD sees it: a farthest-point sample in normalised units, with its part per point.
struct Target {
  Points points;
  Eigen::VectorXi part;
};

Target make_target(const TrainingInstance& instance, const Normalization& normalization, int count) {
  const Points normalised = normalization.apply(instance.points);
  const auto wanted = static_cast<std::size_t>(std::min<Eigen::Index>(count, normalised.rows()));
  const std::vector<int> rows = farthest_point_indices(normalised, wanted);
  Target target{select_rows(normalised, rows), Eigen::VectorXi()};
  if (instance.part.size() > 0) target.part = instance.part(rows);
  return target;
}

bool separate_label_fit(const TrainingSettings& settings) {
  return settings.label_beta > 0.0 && settings.label_beta != settings.beta;
}

// The canonical registered onto `target` by the stiffer CPD that carries part labels (`label_beta`): a field
// of the holistic space's width slides points along the surface and with them the part boundaries.
Points label_fit(const Points& canonical, const Points& target, const TrainingSettings& settings,
                 const std::string& instance, TrainingReport& report, StepCounter& progress) {
  TrainingSettings stiffer = settings;
  stiffer.beta = settings.label_beta;
  return register_onto(canonical, target, stiffer, instance, "labels", report, progress).moved;
}

// A share of `part`'s points (every point's for part -1) for which `agrees` holds.
template <typename Agrees>
double share(const Eigen::VectorXi& truth, int part, Agrees agrees) {
  int total = 0, agreeing = 0;
  for (Eigen::Index i = 0; i < truth.size(); ++i) {
    if (part >= 0 && truth[i] != part) continue;
    ++total;
    agreeing += agrees(i);
  }
  return total ? static_cast<double>(agreeing) / total : 0.0;
}

// `propagated` labels of the normalised `target` against its own (`target.part`) and against every part whose
// surface in `instance`'s mesh passes through each point.
TrainingReport::LabelAgreement agreement(const Target& target, const Eigen::VectorXi& propagated,
                                         const TrainingInstance& instance, const Normalization& normalization,
                                         const std::vector<std::string>& part_names) {
  const int parts = static_cast<int>(part_names.size());
  const Mesh mesh{normalization.apply(instance.mesh.vertices), instance.mesh.faces, {}};
  detail::PartsThrough through = detail::parts_through_points(
      mesh, instance.mesh_vertex_part, parts, target.points, 0.001 * bounding_box_diagonal(target.points));
  for (Eigen::Index i = 0; i < target.points.rows(); ++i)
    through(i, target.part[i]) = true;  // its own part, whatever the mesh (a cloud has none)
  TrainingReport::LabelAgreement result;
  for (int part = -1; part < parts; ++part) {
    const std::string name = part < 0 ? "all" : part_names[static_cast<std::size_t>(part)];
    result.by_surface[name] =
        share(target.part, part, [&](Eigen::Index i) { return through(i, propagated[i]); });
    result.by_sampled_part[name] =
        share(target.part, part, [&](Eigen::Index i) { return propagated[i] == target.part[i]; });
  }
  result.shared_surface = (through.rowwise().count() > 1).cast<double>().mean();
  return result;
}

std::size_t find_canonical(const std::vector<TrainingInstance>& instances, const TrainingSettings& settings,
                           std::string& explanation) {
  if (!settings.canonical) return choose_canonical(instances, &explanation);
  std::string names;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    if (instances[i].name == *settings.canonical) {
      explanation = "given";
      return i;
    }
    names += (names.empty() ? "" : ", ") + instances[i].name;
  }
  throw UsageError("no instance named '" + *settings.canonical + "' (instances: " + names + ")");
}

// Replaces each part that has fewer than `floor` points in `sample` by a farthest-point sample of its own
// rows of `dense` (floor points, or all it has), so small parts are not starved by sampling of the whole.
Target with_part_floor(Target sample, const Target& dense, int part_count, int floor) {
  for (int part = 0; part < part_count; ++part) {
    const std::vector<int> own = rows_with(sample.part, part);
    if (static_cast<int>(own.size()) >= floor) continue;
    const std::vector<int> dense_rows = rows_with(dense.part, part);
    if (dense_rows.empty()) continue;  // a part without surface samples is refused when its space is learned
    const Points dense_part = select_rows(dense.points, dense_rows);
    const auto wanted = std::min<std::size_t>(static_cast<std::size_t>(floor), dense_rows.size());
    const Points added = select_rows(dense_part, farthest_point_indices(dense_part, wanted));
    std::vector<int> kept;  // every row of the other parts
    for (Eigen::Index i = 0; i < sample.part.size(); ++i)
      if (sample.part[i] != part) kept.push_back(static_cast<int>(i));
    Target topped{Points(static_cast<Eigen::Index>(kept.size()) + added.rows(), 3),
                  Eigen::VectorXi(static_cast<Eigen::Index>(kept.size()) + added.rows())};
    topped.points << select_rows(sample.points, kept), added;
    topped.part << sample.part(kept), Eigen::VectorXi::Constant(added.rows(), part);
    sample = std::move(topped);
  }
  return sample;
}

void set_canonical(CategoryModel& model, const TrainingInstance& canonical,
                   const TrainingSettings& settings) {
  model.normalization = Normalization::fit(canonical.points);
  Target sample = make_target(canonical, model.normalization, settings.canonical_points);
  if (model.has_parts() && settings.min_part_points > 0) {
    const Target dense{model.normalization.apply(canonical.points), canonical.part};
    sample =
        with_part_floor(sample, dense, static_cast<int>(model.part_names.size()), settings.min_part_points);
  }
  model.canonical = sample.points;
  model.canonical_part = model.has_parts() ? sample.part : Eigen::VectorXi::Zero(sample.points.rows());
  if (canonical.mesh.faces.rows() == 0) {
    model.mesh_vertex_part.resize(0);
    return;
  }
  model.canonical_mesh.vertices = model.normalization.apply(canonical.mesh.vertices);
  model.canonical_mesh.faces = canonical.mesh.faces;
  model.mesh_vertex_part =
      canonical.mesh_vertex_part.size() == canonical.mesh.vertices.rows()
          ? canonical.mesh_vertex_part
          : propagate_labels(model.canonical, model.canonical_part, model.canonical_mesh.vertices);
}

ShapeSpace learn_space(const std::string& name, const std::vector<int>& rows, const Points& canonical,
                       const TrainingSettings& settings, const std::vector<Points>& weights,
                       StepCounter& progress) {
  PcaEmSettings pca;
  pca.dimensions = settings.latent_dimensions;
  pca.seed = settings.seed;
  ShapeSpace space = learn_shape_space(name, rows, canonical, settings.beta, weights, pca);
  std::ostringstream line;
  line << "space " << name << ": " << space.dimensions() << " dimensions explain "
       << 100.0 * space.explained_fraction().sum() << "% of the training variance";
  progress.step(line.str());
  return space;
}

Eigen::MatrixXd stack_rows(const std::vector<Points>& fields) {
  Eigen::MatrixXd stacked(static_cast<Eigen::Index>(fields.size()), fields.empty() ? 0 : fields[0].size());
  for (std::size_t i = 0; i < fields.size(); ++i)
    stacked.row(static_cast<Eigen::Index>(i)) =
        Eigen::Map<const Eigen::RowVectorXd>(fields[i].data(), fields[i].size());
  return stacked;
}

Points rows_of_part(const Target& target, int part) {
  std::vector<int> rows;
  for (Eigen::Index i = 0; i < target.part.size(); ++i)
    if (target.part[i] == part) rows.push_back(static_cast<int>(i));
  return select_rows(target.points, rows);
}

// The instances' mean diagonal in data units, and the real size it stands for when one was given.
void set_size(CategoryModel& model, const std::vector<TrainingInstance>& instances,
              const TrainingSettings& settings) {
  double total = 0.0;
  for (const TrainingInstance& instance : instances) total += bounding_box_diagonal(instance.points);
  model.data_size = total / static_cast<double>(instances.size());
  if (settings.size > 0.0) model.size = settings.size;
}

}  // namespace

CategoryModel train_category(const std::string& category, const std::vector<TrainingInstance>& instances,
                             const std::vector<std::string>& part_names, const TrainingSettings& settings,
                             TrainingReport* report, const ProgressCallback& progress) {
  TrainingProgressCallback steps;
  if (progress) steps = [&progress](const TrainingProgress& step) { progress(step.line); };
  return train_category(category, instances, part_names, settings, report, steps);
}

CategoryModel train_category(const std::string& category, const std::vector<TrainingInstance>& instances,
                             const std::vector<std::string>& part_names, const TrainingSettings& settings,
                             TrainingReport* report, const TrainingProgressCallback& steps) {
  const auto start = std::chrono::steady_clock::now();
  check_instances(instances, part_names);
  validate(settings);  // the ranges of training_options.hpp, as every front end reads them
  TrainingReport local_report;
  TrainingReport& out = report ? *report : local_report;
  const std::size_t canonical_index = find_canonical(instances, settings, out.canonical_choice);
  const TrainingInstance& canonical = instances[canonical_index];
  if (!part_names.empty() && canonical.part.size() == 0)
    throw InputError("the canonical instance '" + canonical.name + "' has no part labels");

  const int spaces = 1 + static_cast<int>(part_names.size());
  const std::size_t held_out =
      part_names.empty()
          ? 0
          : detail::seam_weight_held_out(instances.size(), canonical_index, settings.seam_weight_candidates)
                .size();
  // Labels are carried to each instance without its own, and to one with its own only to measure the
  // agreement for a caller that asked for the report.
  const auto carries_labels = [&](std::size_t i) {
    return !part_names.empty() && i != canonical_index && (report || instances[i].part.size() == 0);
  };
  std::size_t label_fits = 0;
  for (std::size_t i = 0; i < instances.size(); ++i)
    label_fits += carries_labels(i) && separate_label_fit(settings);
  StepCounter progress(instances.size() * static_cast<std::size_t>(spaces) + held_out + label_fits, steps);
  CategoryModel model;
  model.category = category;
  model.part_names = part_names;
  set_canonical(model, canonical, settings);
  const Eigen::Index m = model.canonical.rows();

  // Holistic: the canonical onto every instance; the canonical itself counts with a zero field.
  std::vector<Target> targets;
  std::vector<Points> holistic_weights;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    Target target = make_target(instances[i], model.normalization, settings.target_points);
    if (i == canonical_index) {
      holistic_weights.push_back(Points::Zero(m, 3));
    } else {
      const CpdRun run = register_onto(model.canonical, target.points, settings, instances[i].name,
                                       "holistic", out, progress);
      holistic_weights.push_back(run.weights);
      if (carries_labels(i)) {
        const Points carrier =
            separate_label_fit(settings)
                ? label_fit(model.canonical, target.points, settings, instances[i].name, out, progress)
                : run.moved;
        const Eigen::VectorXi propagated = propagate_labels(carrier, model.canonical_part, target.points);
        if (target.part.size() > 0)
          out.label_agreement[instances[i].name] =
              agreement(target, propagated, instances[i], model.normalization, part_names);
        else
          target.part = propagated;
      }
    }
    targets.push_back(std::move(target));
  }
  std::vector<int> all_rows(static_cast<std::size_t>(m));
  for (Eigen::Index i = 0; i < m; ++i) all_rows[static_cast<std::size_t>(i)] = static_cast<int>(i);
  model.spaces.push_back(
      learn_space("holistic", all_rows, model.canonical, settings, holistic_weights, progress));
  model.training_weights = stack_rows(holistic_weights);
  std::vector<std::vector<Points>> fields{holistic_weights};  // every space's, for the seam weight's choice

  // One space per part: the canonical part onto the same part of every instance.
  for (int part = 0; part < static_cast<int>(part_names.size()); ++part) {
    const std::vector<int> rows = model.part_rows(part);
    const Points canonical_part = select_rows(model.canonical, rows);
    if (canonical_part.rows() < 10)
      throw InputError("part '" + part_names[part] + "' has " +
                       (canonical_part.rows() == 0
                            ? std::string("no canonical point")
                            : "only " + std::to_string(canonical_part.rows()) + " of the canonical's " +
                                  std::to_string(model.canonical.rows()) + " points") +
                       " after sampling (a part space needs 10): its labelled surface on '" + canonical.name +
                       "' is too small; check the labels or keep more canonical points");
    const detail::SeamRefit seam(model.canonical, model.canonical_part, part, rows, settings.seam_band,
                                 settings.beta);
    std::vector<Points> part_weights;
    for (std::size_t i = 0; i < instances.size(); ++i) {
      if (i == canonical_index) {
        part_weights.push_back(Points::Zero(canonical_part.rows(), 3));
        continue;
      }
      const Points target = rows_of_part(targets[i], part);
      if (target.rows() < 10)
        throw InputError("instance '" + instances[i].name + "' has only " + std::to_string(target.rows()) +
                         " points of part '" + part_names[part] + "'");
      const CpdRun run =
          register_onto(canonical_part, target, settings, instances[i].name, part_names[part], out, progress);
      part_weights.push_back(seam.apply(run.weights, holistic_weights[i]));
    }
    model.spaces.push_back(
        learn_space(part_names[part], rows, canonical_part, settings, part_weights, progress));
    fields.push_back(std::move(part_weights));
  }

  TrainingRecord& record = model.training;
  for (const TrainingInstance& instance : instances) record.instances.push_back(instance.name);
  record.canonical = canonical.name;
  record.canonical_choice = out.canonical_choice;
  record.canonical_points = static_cast<int>(m);
  record.min_part_points = model.has_parts() ? settings.min_part_points : 0;
  record.seam_band = model.has_parts() ? settings.seam_band : 0.0;
  record.beta = settings.beta;
  record.lambda = settings.lambda;
  record.outlier_weight = settings.outlier_weight;
  record.latent_dimensions = settings.latent_dimensions;
  record.seed = settings.seed;
  model.up = settings.up.normalized();
  if (model.has_parts()) {  // last: its registrations use the model as registration will
    std::vector<Points> samples;
    for (const Target& target : targets) samples.push_back(target.points);
    const detail::SeamWeightChoice choice =
        detail::choose_seam_weight(model, fields, samples, canonical_index, settings,
                                   [&progress](const std::string& line) { progress.step(line); });
    record.seam_weight = choice.weight;
    record.seam_weight_choice = choice.explanation;
    record.seam_weight_trials = choice.trials;
  }
  set_size(model, instances, settings);  // after the seam weight's registrations, which run in data units
  model.validate();
  out.seconds = seconds_since(start);
  return model;
}

}  // namespace partreg::core
