// CPD speed on real drills (../shared/data/drills): non-rigid at 500-20000 points, rigid at 1000 and 5000.
// Run: ./build/tests/bench/cpd_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// The 100,000-point case is manual (about 1 CPU second a run, one run):
//   PARTREG_BENCH_100K=1 ./build/tests/bench/cpd_benchmark --benchmark_filter=100000
// PARTREG_BENCH_EXACT=1 runs the exact E-step instead (the fit's reference; minutes from 20,000 points), and
// PARTREG_BENCH_TRACE=1 prints every EM iteration's time and sigma2. The CPU column is the process's (both
// E-step threads), the time column wall time.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>

#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/io/cloud_io.hpp"
#include "support/shared_data.hpp"

namespace {

using partreg::core::Points;

// A drill cloud at exactly `count` points. The files hold 300-550 points, so larger sizes are made by
// scattering new points on small discs in each point's tangent plane (radius: half the mean spacing),
// which keeps the surface and adds no duplicate; smaller sizes by farthest-point sampling.
Points drill_at(const std::string& name, int count) {
  const auto file = partreg::io::read_cloud_file(partreg::testing::shared_data("drills/" + name));
  const Points& points = file.cloud.points;
  if (count <= points.rows())
    return partreg::core::select_rows(points, partreg::core::farthest_point_indices(points, count));
  const partreg::core::KdTree tree(points);
  std::vector<int> index;
  Eigen::VectorXd squared;
  double spacing = 0.0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    std::vector<std::pair<int, double>> near;
    tree.radius(points.row(i).transpose(), 0.02, near);
    double best = 1e9;
    for (const auto& [j, d2] : near)
      if (j != i) best = std::min(best, d2);
    spacing += std::sqrt(std::min(best, 4e-4));
  }
  spacing /= static_cast<double>(points.rows());
  std::mt19937_64 generator(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Points out(count, 3);
  for (int i = 0; i < count; ++i) {
    const Eigen::Index source = i % points.rows();
    const Eigen::Vector3d normal = file.cloud.normals.row(source).normalized();
    const Eigen::Vector3d a = normal.unitOrthogonal(), b = normal.cross(a);
    const double r = i < points.rows() ? 0.0 : 0.5 * spacing;
    out.row(i) = points.row(source) + (r * (uniform(generator) * a + uniform(generator) * b)).transpose();
  }
  return out;
}

// PARTREG_BENCH_EXACT=1: the exact E-step (every pair, plain EM on all points), the reference for the fit.
bool exact_e_step() {
  const char* exact = std::getenv("PARTREG_BENCH_EXACT");
  return exact && std::string(exact) == "1";
}

// PARTREG_BENCH_TRACE=1: one line per EM iteration on stderr (milliseconds since the last, the EM line).
partreg::core::ProgressListener trace_listener() {
  const char* trace = std::getenv("PARTREG_BENCH_TRACE");
  if (!trace || std::string(trace) != "1") return {};
  auto last = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
  return [last](const partreg::core::Progress& p) {
    const auto now = std::chrono::steady_clock::now();
    std::fprintf(stderr, "%8.2f ms  %s\n", std::chrono::duration<double, std::milli>(now - *last).count(),
                 p.line.c_str());
    *last = now;
  };
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// Mean distance from each moved point to its nearest target point: the fit, in normalised units when the
// target's diagonal is 1 (the drills' own units are metres; this divides by the diagonal).
double fit_of_diagonal(const Points& moved, const Points& target) {
  const partreg::core::KdTree tree(target);
  std::vector<int> index;
  Eigen::VectorXd squared;
  tree.nearest_all(moved, index, squared);
  const Eigen::RowVector3d extent = target.colwise().maxCoeff() - target.colwise().minCoeff();
  return squared.cwiseSqrt().mean() / extent.norm();
}

void BM_NonrigidCpdDrills(benchmark::State& state) {
  const auto data = partreg::testing::shared_data("drills/drill_1.pcd");
  if (!std::filesystem::exists(data)) {
    state.SkipWithError("shared data absent: ../shared/data/drills");
    return;
  }
  const int count = static_cast<int>(state.range(0));
  const Points source = drill_at("drill_1.pcd", count), target = drill_at("drill_4.pcd", count);
  partreg::core::NonrigidCpdSettings settings;  // beta = 2, lambda = 2 (normalised units)
  settings.progress = trace_listener();
  settings.exact_e_step = exact_e_step();
  int iterations = 0;
  double fit = 0.0;
  for (auto _ : state) {
    const auto result = partreg::core::register_nonrigid(source, target, settings);
    iterations = result.iterations;
    fit = fit_of_diagonal(result.moved, target);
    benchmark::DoNotOptimize(result.moved.data());
  }
  state.counters["em_iterations"] = iterations;
  state.counters["fit_of_diagonal"] = fit;
  state.counters["peak_rss_MB"] = peak_rss_mb();
}
BENCHMARK(BM_NonrigidCpdDrills)
    ->Arg(500)
    ->Arg(1000)
    ->Arg(2000)
    ->Arg(5000)
    ->Arg(20000)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

void BM_RigidCpdDrills(benchmark::State& state) {
  const auto data = partreg::testing::shared_data("drills/drill_1.pcd");
  if (!std::filesystem::exists(data)) {
    state.SkipWithError("shared data absent: ../shared/data/drills");
    return;
  }
  const int count = static_cast<int>(state.range(0));
  const Points source = drill_at("drill_1.pcd", count), target = drill_at("drill_4.pcd", count);
  int iterations = 0;
  double fit = 0.0;
  for (auto _ : state) {
    partreg::core::RigidCpdSettings settings;
    settings.progress = trace_listener();
    settings.exact_e_step = exact_e_step();
    const auto result = partreg::core::register_rigid(source, target, settings);
    iterations = result.iterations;
    fit = fit_of_diagonal(result.moved, target);
    benchmark::DoNotOptimize(result.moved.data());
  }
  state.counters["em_iterations"] = iterations;
  state.counters["fit_of_diagonal"] = fit;
  state.counters["peak_rss_MB"] = peak_rss_mb();
}
BENCHMARK(BM_RigidCpdDrills)
    ->Arg(1000)
    ->Arg(5000)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  // 100,000 points only on request: one run takes tens of seconds.
  if (const char* huge = std::getenv("PARTREG_BENCH_100K"); huge && std::string(huge) == "1")
    benchmark::RegisterBenchmark("BM_NonrigidCpdDrills", BM_NonrigidCpdDrills)
        ->Arg(100000)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->UseRealTime();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
