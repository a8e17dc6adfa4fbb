#include "partreg/eval/protocol.hpp"

#include "grasp_scoring.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/eval/baselines.hpp"

namespace partreg::eval {
namespace {

using Clock = std::chrono::steady_clock;

// One way an instance is seen before any perturbation: the full view or one partial view.
struct Observation {
  int view = -1;
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  core::Points points;
  std::optional<Eigen::Vector3d> viewpoint;
};

// What a tested instance's registrations are scored against, in its own frame.
struct Truth {
  core::Points points;
  Eigen::VectorXi part;  // the truth's own part per point; empty when it has none
};

// Everything about one tested instance that does not depend on the model.
struct TestCase {
  std::size_t instance = 0;  // index into EvalInput::instances
  int fold = 0;
  Truth truth;
  double diagonal = 0.0;                  // D of the truth (truth_errors.hpp)
  std::vector<Observation> observations;  // full view first, then partial views in direction order
};

// One observation under one perturbation level; it yields one row per variant.
struct Job {
  std::size_t observation = 0;
  Perturbation kind = Perturbation::none;
  int level_index = -1;
};

std::uint64_t mix(std::uint64_t seed, std::uint64_t value) { return mix_seed(seed, value); }

// The observations the sweeps perturb: the full view and `sweep_views` partial views spread evenly over the
// direction list (every k-th), so that they look at the object from all round.
std::vector<std::size_t> swept_observations(const TestCase& test, const Protocol& protocol) {
  std::vector<std::size_t> swept = {0};
  const std::size_t partial = test.observations.size() - 1;
  const std::size_t count = std::min<std::size_t>(partial, static_cast<std::size_t>(protocol.sweep_views));
  for (std::size_t i = 0; i < count; ++i) swept.push_back(1 + i * partial / count);
  return swept;
}

std::vector<Job> plan_jobs(const TestCase& test, const Protocol& protocol) {
  std::vector<Job> jobs;
  for (std::size_t o = 0; o < test.observations.size(); ++o) jobs.push_back({o, Perturbation::none, -1});
  const std::vector<std::size_t> swept = swept_observations(test, protocol);
  for (Perturbation kind : protocol.sweeps)
    for (int level : planned_levels(kind, protocol))
      for (std::size_t o : swept) jobs.push_back({o, kind, level});
  return jobs;
}

std::vector<core::Variant> usable_variants(const EvalInput& input, const EvalSettings& settings,
                                           const EvalProgress& progress) {
  std::vector<core::Variant> variants;
  for (core::Variant variant : settings.variants) {
    const bool needs_parts = variant != core::Variant::holistic;
    if (needs_parts && input.part_names.empty()) {
      if (progress)
        progress({0, 0, input.category + " has no parts: " + core::enum_name(variant) + " is not run"});
      continue;
    }
    if (std::find(variants.begin(), variants.end(), variant) == variants.end()) variants.push_back(variant);
  }
  if (variants.empty()) variants.push_back(core::Variant::holistic);
  return variants;
}

// The truth of a mesh instance is a sample of its own (EvalSettings::truth_points), each point with its
// face's part, so that the truth's spacing, not the training sample's, bounds the forward half. Cloud data,
// an instance whose parts are given per point rather than per mesh vertex, and truth_points 0 keep the
// instance's own points.
Truth truth_of(const core::TrainingInstance& instance, const EvalSettings& settings, std::uint64_t seed) {
  const core::Mesh& mesh = instance.mesh;
  const bool parts_on_mesh =
      instance.part.size() == 0 || instance.mesh_vertex_part.size() == mesh.vertices.rows();
  if (mesh.faces.rows() == 0 || settings.truth_points == 0 || !parts_on_mesh)
    return {instance.points, instance.part};
  Eigen::VectorXi face;
  Truth truth{core::sample_surface(mesh, static_cast<std::size_t>(settings.truth_points), seed, &face).points,
              {}};
  if (instance.part.size() == 0) return truth;
  truth.part.resize(face.size());
  for (Eigen::Index i = 0; i < face.size(); ++i)
    truth.part[i] = instance.mesh_vertex_part[mesh.faces(face[i], 0)];
  return truth;
}

TestCase make_test_case(const EvalInput& input, std::size_t index, int fold, const EvalSettings& settings,
                        const std::vector<Eigen::Vector3d>& directions, const EvalProgress& progress) {
  const core::TrainingInstance& instance = input.instances[index];
  TestCase test{index, fold, truth_of(instance, settings, mix(mix(settings.seed, index), 1)), 0.0, {}};
  test.diagonal = core::truth_diagonal(test.truth.points);
  const bool has_mesh = instance.mesh.faces.rows() > 0;
  Observation full;
  full.points =
      has_mesh
          ? core::sample_surface(instance.mesh, settings.full_view_points, mix(settings.seed, index)).points
          : instance.points;
  test.observations.push_back(std::move(full));
  if (directions.empty()) return test;
  const ViewCaster caster = has_mesh ? ViewCaster(instance.mesh) : ViewCaster(instance.points);
  for (std::size_t v = 0; v < directions.size(); ++v) {
    View view = caster.cast(directions[v], settings.camera);
    if (view.points.rows() < 30) {
      if (progress)
        progress({0, 0, instance.name + ": view " + std::to_string(v) + " sees too little, skipped"});
      continue;
    }
    Observation observation{static_cast<int>(v), view.direction, std::move(view.points), std::nullopt};
    if (settings.use_viewpoint) observation.viewpoint = view.viewpoint;
    test.observations.push_back(std::move(observation));
  }
  return test;
}

// Where each canonical point truly lies on the tested instance: the canonical's nearest ground-truth row,
// taken on the tested instance (rows are the same semantic points on every instance).
std::optional<core::Points> true_correspondents(const EvalInput& input, const core::CategoryModel& model,
                                                const std::string& instance) {
  const auto canonical = input.correspondences.find(model.training.canonical);
  const auto tested = input.correspondences.find(instance);
  if (canonical == input.correspondences.end() || tested == input.correspondences.end()) return std::nullopt;
  if (canonical->second.rows() != tested->second.rows())
    throw InputError("ground-truth correspondences of " + instance + " and " + model.training.canonical +
                     " have different row counts");
  std::vector<int> nearest;
  Eigen::VectorXd squared;
  core::KdTree(canonical->second).nearest_all(model.normalization.undo(model.canonical), nearest, squared);
  return core::select_rows(tested->second, nearest);
}

// What one fold shares between its jobs.
struct FoldContext {
  const core::CategoryModel& model;
  const std::vector<Template>& templates;  // empty without baselines
  const std::vector<core::Grasp>& grasps;  // the canonical's grasps; empty without EvalSettings::grasps
  const core::Gripper& gripper;            // EvalSettings::grasps' gripper in the fold's data units
};

std::size_t rows_per_job(const EvalSettings& settings, const std::vector<core::Variant>& variants) {
  return variants.size() + (settings.baselines ? core::EnumNames<Baseline>::table.size() : 0);
}

// partreg's holistic pose on this observation: a variant's holistic fit where one ran (holistic and
// hol+part fit the whole object first), else a holistic registration of its own.
Eigen::Matrix4d holistic_pose(const core::CategoryModel& model, const core::Points& observed,
                              core::RegistrationSettings registration,
                              const std::vector<core::RegistrationResult>& results) {
  for (const core::RegistrationResult& result : results)
    if (!result.fits.empty() && result.fits.front().space == model.holistic().name)
      return result.fits.front().T_observed_canonical;
  registration.variant = core::Variant::holistic;
  return core::register_observation(model, observed, registration).fits.front().T_observed_canonical;
}

// Registers every variant on one perturbed observation and measures each against the moved ground truth;
// then the baselines on the same observation and truth.
void run_job(const EvalInput& input, const EvalSettings& settings, const FoldContext& fold,
             const TestCase& test, const std::optional<core::Points>& correspondents, const Job& job,
             const std::vector<core::Variant>& variants, EvalRow* rows) {
  const core::CategoryModel& model = fold.model;
  const core::TrainingInstance& instance = input.instances[test.instance];
  const Observation& observation = test.observations[job.observation];
  const double paper_level = job.level_index < 0 ? 0.0 : sweep_levels(job.kind)[job.level_index];
  const double level = relative_level(job.kind, paper_level);
  const std::uint64_t seed = mix(mix(mix(settings.seed, test.instance), observation.view + 1),
                                 static_cast<std::uint64_t>(job.kind) * 16 + (job.level_index + 1));
  const Eigen::Vector3d up =
      core::with_model_defaults(settings.registration, model).initialisation.up.value();
  const Perturbed perturbed = perturb(observation.points, job.kind, level, test.diagonal, seed, up);
  const core::KdTree truth(
      moved_by(test.truth.points, perturbed.T_perturbed_original));  // shared by the variants
  const std::optional<core::Points> truth_of_row =
      correspondents ? std::optional<core::Points>(moved_by(*correspondents, perturbed.T_perturbed_original))
                     : std::nullopt;
  core::RegistrationSettings registration = settings.registration;
  if (observation.viewpoint) registration.viewpoint = perturbed.T_perturbed_original * *observation.viewpoint;
  const auto make_row = [&](const std::string& name, const core::TruthErrors& errors, double seconds) {
    return EvalRow{input.category,
                   instance.name,
                   model.training.canonical,
                   name,
                   test.fold,
                   observation.view,
                   observation.direction,
                   job.kind,
                   job.level_index,
                   paper_level,
                   level,
                   test.diagonal,
                   static_cast<int>(perturbed.points.rows()),
                   errors,
                   seconds,
                   std::nullopt,
                   std::nullopt,
                   std::nullopt,
                   std::nullopt,
                   std::nullopt,
                   std::nullopt};
  };
  // The truth's own parts (part files, or a labels file of its own) score each part against its own.
  const bool truth_has_parts =
      !model.part_names.empty() && test.truth.part.size() == test.truth.points.rows();
  // The gripper test runs on the true mesh where the instance has one.
  const bool judge_grasps = !fold.grasps.empty() && instance.mesh.faces.rows() > 0;
  std::optional<MeshRays> true_mesh;
  if (judge_grasps) {
    core::Mesh moved = instance.mesh;
    moved.vertices = moved_by(instance.mesh.vertices, perturbed.T_perturbed_original);
    true_mesh.emplace(moved);
  }
  const detail::GraspJudge judge{&fold.grasps,  &fold.gripper,
                                 true_mesh ? &*true_mesh : nullptr, &truth, test.diagonal, &perturbed.points,
                                 truth_of_row ? &*truth_of_row : nullptr};
  std::vector<core::RegistrationResult> results;
  for (std::size_t v = 0; v < variants.size(); ++v) {
    registration.variant = variants[v];
    results.push_back(core::register_observation(model, perturbed.points, registration));
    rows[v] =
        make_row(core::enum_name(variants[v]),
                 core::measure_against_truth(results[v].deformed, results[v].part, model.part_names, truth,
                                             test.diagonal, truth_of_row ? &*truth_of_row : nullptr,
                                             truth_has_parts ? &test.truth.part : nullptr),
                 results[v].seconds);
    // Correspondences are the material points' (the refinement may slide the surface, not what it carries).
    if (truth_of_row)
      rows[v].errors.correspondence_per_diagonal = core::correspondence_error(
          core::deform_points(model, results[v], model.normalization.undo(model.canonical), {},
                              core::Follow::material),
          *truth_of_row, test.diagonal);
    if (variants[v] != core::Variant::holistic) rows[v].seam = core::seam_gap(model, results[v]);
    if (model.canonical_mesh.faces.rows() > 0) rows[v].mesh_stretch = results[v].figures.mesh_stretch;
    rows[v].figures = results[v].figures;
    rows[v].verdict = results[v].assessment.verdict;
    if (judge_grasps) rows[v].grasps = detail::registration_grasps(judge, model, results[v]);
  }
  if (!settings.baselines) return;
  // The full view's sample is independent of the truth's (for cloud data it is the truth itself).
  const core::Points true_shape =
      moved_by(true_shape_points(model, test.observations.front().points), perturbed.T_perturbed_original);
  BaselineObservation seen{&perturbed.points,
                           &truth,
                           test.diagonal,
                           truth_of_row ? &*truth_of_row : nullptr,
                           holistic_pose(model, perturbed.points, registration, results),
                           &true_shape};
  const std::vector<Eigen::Matrix3d> starts =
      start_rotations(settings.registration.initialisation.restarts, up);
  const std::vector<BaselineScore> scores = score_baselines(model, fold.templates, seen, starts);
  for (std::size_t b = 0; b < scores.size(); ++b) {
    EvalRow& row = rows[variants.size() + b];
    row = make_row(core::enum_name(scores[b].baseline), scores[b].errors, scores[b].seconds);
    if (judge_grasps && scores[b].baseline == Baseline::rigid_canonical)
      row.grasps = detail::rigid_grasps(judge, model, scores[b].T_observed_shape);
  }
}

// Fold of every instance that may be tested: its position among them (leave-one-out) or that modulo k.
std::map<std::string, int> assign_folds(const EvalInput& input, const Protocol& protocol) {
  std::map<std::string, int> fold;
  int position = 0;
  for (const core::TrainingInstance& instance : input.instances)
    if (instance.name != input.fixed_canonical) {
      fold[instance.name] = protocol.folds > 0 ? position % protocol.folds : position;
      ++position;
    }
  return fold;
}

std::vector<core::TrainingInstance> training_set(const EvalInput& input,
                                                 const std::map<std::string, int>& folds, int fold) {
  std::vector<core::TrainingInstance> training;
  for (const core::TrainingInstance& instance : input.instances) {
    const auto found = folds.find(instance.name);
    if (found == folds.end() || found->second != fold) training.push_back(instance);
  }
  if (training.size() < 2)
    throw InputError("fold " + std::to_string(fold) + " of " + input.category + " leaves " +
                     std::to_string(training.size()) + " instance to train on (at least 2 are needed)");
  return training;
}

// The fold's training instances as indices (TestedInstance::training).
std::vector<std::size_t> training_indices(const EvalInput& input, const std::map<std::string, int>& folds,
                                          int fold) {
  std::vector<std::size_t> training;
  for (std::size_t i = 0; i < input.instances.size(); ++i) {
    const auto found = folds.find(input.instances[i].name);
    if (found == folds.end() || found->second != fold) training.push_back(i);
  }
  return training;
}

TestedInstance tested_view(const EvalInput& input, const std::map<std::string, int>& folds,
                           const TestCase& test) {
  TestedInstance tested;
  tested.index = test.instance, tested.fold = test.fold, tested.diagonal = test.diagonal;
  tested.truth = &test.truth.points, tested.truth_part = &test.truth.part;
  tested.training = training_indices(input, folds, test.fold);
  return tested;
}

std::size_t extra_rows(const EvalInput& input, const EvalSettings& settings,
                       const std::map<std::string, int>& folds, const TestCase& test, std::size_t variants) {
  if (!settings.extra) return 0;
  return static_cast<std::size_t>(settings.extra->jobs(input, tested_view(input, folds, test))) *
         settings.extra->rows_per_job(variants);
}

// The extra observations of one tested instance (EvalSettings::extra) on the fold's model, their rows appended
// to `rows` in job order (after the instance's own); `finished` hears of each job's rows as it ends.
void run_extra(const EvalInput& input, const EvalSettings& settings, const core::CategoryModel& model,
               const TestedInstance& tested, const std::vector<core::Variant>& variants, tbb::task_arena& arena,
               std::vector<EvalRow>& rows, const std::function<void(std::size_t)>& finished) {
  const int jobs = settings.extra->jobs(input, tested);
  const std::size_t first = rows.size(), per_job = settings.extra->rows_per_job(variants.size());
  rows.resize(first + static_cast<std::size_t>(jobs) * per_job);
  arena.execute([&] {
    tbb::parallel_for(0, jobs, [&](int j) {
      const core::ThreadBudget one(1);  // the arena holds the budget, as for the instance's own jobs
      settings.extra->run(input, settings, model, tested, j, variants,
                          &rows[first + static_cast<std::size_t>(j) * per_job]);
      finished(per_job);
    });
  });
}

std::size_t index_of(const EvalInput& input, const std::string& name) {
  for (std::size_t i = 0; i < input.instances.size(); ++i)
    if (input.instances[i].name == name) return i;
  throw InputError("no instance named " + name);
}

}  // namespace

std::vector<EvalRow> run_evaluation(const EvalInput& input, const EvalSettings& settings,
                                    const EvalProgress& progress) {
  const std::vector<std::string> tested = tested_instances(input, settings);
  const std::vector<core::Variant> variants = usable_variants(input, settings, progress);
  const std::map<std::string, int> folds = assign_folds(input, settings.protocol);
  const std::vector<Eigen::Vector3d> directions = settings.protocol.views > 0
                                                      ? sphere_directions(settings.protocol.views)
                                                      : std::vector<Eigen::Vector3d>{};

  // Views are cheap: cast them all first, so the total is known before the first registration.
  std::map<int, std::vector<TestCase>> tests_by_fold;
  std::size_t total = 0;
  for (const std::string& name : tested) {
    TestCase test =
        make_test_case(input, index_of(input, name), folds.at(name), settings, directions, progress);
    total += plan_jobs(test, settings.protocol).size() * rows_per_job(settings, variants) +
             extra_rows(input, settings, folds, test, variants.size());
    tests_by_fold[test.fold].push_back(std::move(test));
  }

  std::vector<EvalRow> rows;
  rows.reserve(total);
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  for (const auto& [fold, tests] : tests_by_fold) {
    core::TrainingSettings training = settings.training;
    if (!input.fixed_canonical.empty()) training.canonical = input.fixed_canonical;
    const auto start = Clock::now();
    const std::vector<core::TrainingInstance> instances = training_set(input, folds, fold);
    const core::CategoryModel model =
        core::train_category(input.category, instances, input.part_names, training);
    const std::vector<Template> templates =
        settings.baselines ? fold_templates(model, instances) : std::vector<Template>{};
    const core::Gripper gripper =
        settings.grasps ? settings.grasps->gripper.in_units(model.observed_diagonal()) : core::Gripper{};
    const std::vector<core::Grasp> grasps =
        settings.grasps ? detail::fold_grasps(model, gripper, *settings.grasps, mix(settings.seed, fold + 1))
                        : std::vector<core::Grasp>{};
    const FoldContext context{model, templates, grasps, gripper};
    if (progress) {
      std::ostringstream line;
      line << "fold " << fold << ": trained on " << model.training.instances.size() << " instances in "
           << std::chrono::duration<double>(Clock::now() - start).count() << " s (canonical "
           << model.training.canonical;
      if (model.training.seam_weight) line << ", coupled seam weight " << *model.training.seam_weight;
      line << ")";
      progress({done, total, line.str(), /*bounded=*/false, /*aside=*/true});
    }
    for (const TestCase& test : tests) {
      const std::optional<core::Points> correspondents =
          true_correspondents(input, model, input.instances[test.instance].name);
      const std::vector<Job> jobs = plan_jobs(test, settings.protocol);
      const std::size_t first = rows.size(), per_job = rows_per_job(settings, variants);
      rows.resize(first + jobs.size() * per_job);
      arena.execute([&] {
        tbb::parallel_for(std::size_t{0}, jobs.size(), [&](std::size_t j) {
          const core::ThreadBudget one(1);  // the arena holds the budget: registrations inside stay serial
          run_job(input, settings, context, test, correspondents, jobs[j], variants,
                  &rows[first + j * per_job]);
          const std::size_t now = done += per_job;
          if (progress) {
            const std::lock_guard<std::mutex> lock(progress_mutex);
            progress({now, total, ""});
          }
        });
      });
      if (!settings.extra) continue;
      TestedInstance tested = tested_view(input, folds, test);
      tested.correspondents = correspondents ? &*correspondents : nullptr;
      run_extra(input, settings, model, tested, variants, arena, rows, [&](std::size_t finished) {
        const std::size_t now = done += finished;
        if (progress) {
          const std::lock_guard<std::mutex> lock(progress_mutex);
          progress({now, total, ""});
        }
      });
    }
  }
  return rows;
}

}  // namespace partreg::eval
