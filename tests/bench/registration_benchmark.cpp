// Registration speed on real data: kettles (4 parts) trained with the default floor of points per part (M = 1185),
// observed N = 2000 of a 4000-point sample, q = 4; one benchmark at M = 1000 exactly (no floor).
// Run: ./build/tests/bench/registration_benchmark --benchmark_repetitions=5
// --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <functional>
#include <map>

#include "partreg/core/parallel.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/eval/views.hpp"
#include "partreg/io/dataset.hpp"
#include "support/shared_data.hpp"

namespace {

struct Setup {
  partreg::core::CategoryModel model;
  partreg::core::Points observed;
  partreg::eval::View side;  // one side of `observed`, as a depth camera beside it sees it
};

// Trains on all but the last instance and observes the last one (4000 points sampled from its surface).
// `part_points`: training's floor of canonical points per part (the default gives the kettles M = 1185; 0
// keeps M = 1000 exactly).
const Setup* setup_for(const std::string& folder, int part_points) {
  static std::map<std::pair<std::string, int>, Setup> cache;
  const auto key = std::make_pair(folder, part_points);
  if (cache.count(key)) return &cache[key];
  const auto path = partreg::testing::shared_data(folder);
  if (!std::filesystem::exists(path)) return nullptr;
  partreg::io::DatasetOptions options;
  options.points_per_instance = 4000;
  partreg::io::Dataset dataset = partreg::io::read_dataset(path, options);
  Setup setup;
  setup.observed = dataset.instances.back().points;
  setup.side = partreg::eval::ViewCaster(setup.observed).cast(Eigen::Vector3d(1.0, 0.3, 0.2).normalized());
  dataset.instances.pop_back();
  partreg::core::TrainingSettings training;
  training.min_part_points = part_points;
  setup.model = partreg::core::train_category(dataset.name, dataset.instances, dataset.part_names, training);
  return &(cache[key] = std::move(setup));
}

using Adjust = std::function<void(partreg::core::RegistrationSettings&)>;

// The default settings for `variant`, changed by `adjust`; `threads` as ThreadBudget counts them (0 = all);
// `one_side`: the observation is the setup's side view, its viewpoint known, instead of the whole cloud.
void run(benchmark::State& state, const std::string& folder, partreg::core::Variant variant,
         const Adjust& adjust = {}, int threads = 0,
         int part_points = partreg::core::TrainingSettings{}.min_part_points, bool one_side = false) {
  const Setup* setup = setup_for(folder, part_points);
  if (!setup) {
    state.SkipWithError(("shared data absent: ../shared/data/" + folder).c_str());
    return;
  }
  partreg::core::RegistrationSettings settings;
  settings.variant = variant;
  settings.refinement.enabled = false;  // the space fit; BM_KettleHolisticRefinedSerial adds the refinement
  if (adjust) adjust(settings);
  // The observation holds 4000 points; the default settings match a farthest-point subset of 2000 of them
  // (docs/registration.md).
  const partreg::core::ThreadBudget budget(threads);
  partreg::core::RegistrationResult result;
  if (one_side) settings.viewpoint = setup->side.viewpoint;
  const partreg::core::Points& observed = one_side ? setup->side.points : setup->observed;
  for (auto _ : state) result = partreg::core::register_observation(setup->model, observed, settings);
  state.counters["M"] = static_cast<double>(setup->model.canonical.rows());
  state.counters["fit_of_diagonal"] = result.fit.mean_normalised;
  if (settings.refinement.enabled) state.counters["refine_ms"] = 1e3 * result.refinement.seconds;
  state.counters["last_fit_steps"] = result.fits.back().iterations;  // outer steps of the last space fitted
  if (variant == partreg::core::Variant::coupled)  // training chose it for the benchmark's model
    state.counters["seam_weight"] =
        *partreg::core::with_model_defaults(settings, setup->model).objective.seam_weight;
}

// One start: one yaw and no tilt (the single-start path).
void one_start(partreg::core::RegistrationSettings& settings) {
  settings.initialisation.restarts = 1;
  settings.initialisation.max_tilt = 0.0;
}

using partreg::core::Variant;

// The default search: 12 yaws x 9 tilts, screened on 300 points, successive halving to 2 finalists.
void BM_KettleHolistic(benchmark::State& state) { run(state, "kettles", Variant::holistic); }
void BM_KettleHolPart(benchmark::State& state) { run(state, "kettles", Variant::hol_part); }
// Single-start targets: holistic at most 20 ms, hol+part (four parts) at most 60 ms.
void BM_KettleHolisticOneStart(benchmark::State& state) {
  run(state, "kettles", Variant::holistic, one_start);
}
void BM_KettleHolPartOneStart(benchmark::State& state) {
  run(state, "kettles", Variant::hol_part, one_start);
}
// The search over 12 yaws alone (no tilts), screened on every point (the search before coarse screening).
void BM_KettleHolisticSearch12(benchmark::State& state) {
  run(state, "kettles", Variant::holistic, [](auto& settings) {
    settings.initialisation.max_tilt = 0.0;
    settings.initialisation.screening_points = 0;
  });
}
// The coupled variant, four parts (the holistic search it starts from included).
void BM_KettleCoupled(benchmark::State& state) { run(state, "kettles", Variant::coupled); }
// With one start: minus BM_KettleHolisticOneStart, the time of the coupled problem alone.
void BM_KettleCoupledOneStart(benchmark::State& state) { run(state, "kettles", Variant::coupled, one_start); }
// The coupled problem's reference size: M = 1000 (no floor per part), N = 2000, four parts, one start.
void BM_KettleCoupledOneStartM1000(benchmark::State& state) {
  run(state, "kettles", Variant::coupled, one_start, 0, /*part_points=*/0);
}
void BM_DrillHolistic(benchmark::State& state) { run(state, "drills", Variant::holistic); }
// The fit beyond the space (refinement.hpp) after the default holistic registration, on one thread so that
// the CPU time is all the work (the machine may be shared): the difference between the two is the
// refinement's cost (target: at most 100 ms more).
void BM_KettleHolisticSerial(benchmark::State& state) { run(state, "kettles", Variant::holistic, {}, 1); }
void BM_KettleHolisticRefinedSerial(benchmark::State& state) {
  run(
      state, "kettles", Variant::holistic, [](auto& settings) { settings.refinement.enabled = true; }, 1);
}

// The same on one side of the kettle (a partial view, its viewpoint known): the refinement anchors the
// unseen points to the space's shape.
void BM_KettleSideHolisticSerial(benchmark::State& state) {
  run(state, "kettles", Variant::holistic, {}, 1, partreg::core::TrainingSettings{}.min_part_points, true);
}
void BM_KettleSideHolisticRefinedSerial(benchmark::State& state) {
  run(
      state, "kettles", Variant::holistic, [](auto& settings) { settings.refinement.enabled = true; }, 1,
      partreg::core::TrainingSettings{}.min_part_points, true);
}

BENCHMARK(BM_KettleHolisticOneStart)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KettleHolisticSearch12)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KettleHolistic)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KettleHolisticSerial)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KettleHolisticRefinedSerial)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KettleSideHolisticSerial)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KettleSideHolisticRefinedSerial)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KettleHolPart)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KettleHolPartOneStart)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KettleCoupled)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KettleCoupledOneStart)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KettleCoupledOneStartM1000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DrillHolistic)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
