// The speed of a robot's registrations on real mugs (a model trained on all but the last mug, M = 1000 canonical
// points): a partial view of the held-out mug with the default search, the same with the cheapest look
// pruning the starts, a later frame of a turning stream warm-started from the frame before, and a million-point
// cloud of the mug (a depth camera's full resolution) prepared and registered. One thread, so the CPU time is all
// the work. Each reports where its time went (core::StageSeconds, milliseconds, of the last run).
// Run: ./build/tests/bench/speed_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <optional>

#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/mesh_io.hpp"
#include "support/shared_data.hpp"
#include "support/turning_sequence.hpp"

namespace {

struct Setup {
  partreg::core::CategoryModel model;
  std::vector<partreg::testing::TurningFrame> frames;  // the held-out mug turning, 3 degrees a frame
  partreg::core::Points million;                       // a million points of the held-out mug's surface
};

const Setup* setup() {
  static std::optional<Setup> cached;
  if (cached) return &*cached;
  const auto path = partreg::testing::shared_data("mugs");
  if (!std::filesystem::exists(path)) return nullptr;
  partreg::io::Dataset dataset = partreg::io::read_dataset(path, {});
  Setup s;
  const partreg::core::Points held_out = dataset.instances.back().points;
  dataset.instances.pop_back();
  s.model = partreg::core::train_category(dataset.name, dataset.instances, dataset.part_names, {});
  s.frames = partreg::testing::turning_sequence(held_out, s.model.up, Eigen::Vector3d(1.0, 0.4, 0.3).normalized(),
                                                2, 0.05);
  std::vector<std::filesystem::path> meshes;
  for (const auto& entry : std::filesystem::directory_iterator(path))
    if (entry.path().extension() == ".obj") meshes.push_back(entry.path());
  std::sort(meshes.begin(), meshes.end());
  s.million = partreg::core::sample_surface(partreg::io::read_mesh(meshes.back()), 1000000, 1).points;
  cached = std::move(s);
  return &*cached;
}

void report(benchmark::State& state, const partreg::core::RegistrationResult& result) {
  const partreg::core::StageSeconds& t = result.stages;
  state.counters["prepare_ms"] = 1e3 * t.prepare;
  state.counters["search_ms"] = 1e3 * t.search;
  state.counters["fits_ms"] = 1e3 * t.fits;
  state.counters["refine_ms"] = 1e3 * t.refinement;
  state.counters["stats_ms"] = 1e3 * t.statistics;
  state.counters["fit_of_diagonal"] = result.fit.mean_normalised;
}

// A registration of `observed` per iteration, on one thread; `warm`: started there.
void run(benchmark::State& state, const partreg::core::Points& observed,
         const partreg::core::RegistrationSettings& settings,
         const std::optional<partreg::core::WarmStart>& warm = std::nullopt) {
  const Setup* s = setup();
  if (!s) {
    state.SkipWithError("shared data absent: ../shared/data/mugs");
    return;
  }
  const partreg::core::ThreadBudget one(1);
  partreg::core::RegistrationResult result;
  for (auto _ : state)
    result = warm ? partreg::core::register_observation(s->model, observed, settings, *warm)
                  : partreg::core::register_observation(s->model, observed, settings);
  report(state, result);
}

partreg::core::RegistrationSettings seen_from(const partreg::testing::TurningFrame& frame) {
  partreg::core::RegistrationSettings settings;
  settings.viewpoint = frame.viewpoint;
  return settings;
}

// The default registration (search of 108 starts, refinement) of the partial view.
void BM_MugPartialDefault(benchmark::State& state) {
  if (const Setup* s = setup()) run(state, s->frames[0].observed, seen_from(s->frames[0]));
  else state.SkipWithError("shared data absent");
}

// The same with only the best `survivors` starts after the cheapest look screened.
void BM_MugPartialSurvivors(benchmark::State& state) {
  const Setup* s = setup();
  if (!s) return state.SkipWithError("shared data absent");
  partreg::core::RegistrationSettings settings = seen_from(s->frames[0]);
  settings.initialisation.survivors = static_cast<int>(state.range(0));
  run(state, s->frames[0].observed, settings);
}

// A later frame warm from the one before (with and without the refinement).
void BM_MugWarmFrame(benchmark::State& state) {
  const Setup* s = setup();
  if (!s) return state.SkipWithError("shared data absent");
  const partreg::core::RegistrationResult first =
      partreg::core::register_observation(s->model, s->frames[0].observed, seen_from(s->frames[0]));
  partreg::core::RegistrationSettings settings = seen_from(s->frames[1]);
  settings.refinement.enabled = state.range(0) != 0;
  run(state, s->frames[1].observed, settings, partreg::core::warm_start_of(first));
}

// A million points of the mug's surface, registered with the defaults (no viewpoint).
void BM_MugMillionPoints(benchmark::State& state) {
  if (const Setup* s = setup()) run(state, s->million, {});
  else state.SkipWithError("shared data absent");
}

BENCHMARK(BM_MugPartialDefault)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MugPartialSurvivors)->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MugWarmFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MugMillionPoints)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
