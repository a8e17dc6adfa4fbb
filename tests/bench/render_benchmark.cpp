// Headless frame time with Mesa's llvmpipe: a 1280x960 frame of 100,000 splats plus a 50,000-triangle mesh
// (target: under 250 ms), drawn and read back, and its parts alone.
// Run: ./build/tests/bench/render_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>

#include "partreg/render/headless.hpp"

namespace {

using namespace partreg;

constexpr double kPi = 3.14159265358979323846;

// 100,000 points on a wavy cylinder beside the sphere, coloured in four parts by height.
render::PointSet splats(int count) {
  render::PointSet set;
  set.positions.resize(count, 3);
  Eigen::VectorXi part(count);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = -1.0 + 2.0 * (i + 0.5) / count, phi = golden * i;
    const double radius = 0.6 + 0.08 * std::sin(5.0 * y + 3.0 * phi);
    set.positions.row(i) << 1.5 + radius * std::cos(phi), y, radius * std::sin(phi);
    part[i] = static_cast<int>((y + 1.0) * 2.0) % 4;
  }
  set.colors = render::part_colors(part);
  return set;
}

// A UV sphere of `rings` x `segments` quads: 2 * rings * segments triangles.
render::MeshItem sphere(int rings, int segments) {
  render::MeshItem item;
  core::Mesh& mesh = item.mesh;
  mesh.vertices.resize((rings + 1) * segments, 3);
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = kPi * r / rings, phi = 2.0 * kPi * s / segments;
      mesh.vertices.row(r * segments + s) << std::sin(theta) * std::sin(phi) - 1.0, std::cos(theta),
          std::sin(theta) * std::cos(phi);
    }
  mesh.faces.resize(2 * rings * segments, 3);
  for (int r = 0, f = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      mesh.faces.row(f++) << a, a + segments, b;
      mesh.faces.row(f++) << b, a + segments, b + segments;
    }
  item.color = render::part_color(2);
  return item;
}

void frame(benchmark::State& state, bool with_splats, bool with_mesh) {
  render::RenderSettings settings;  // 1280 x 960
  settings.antialiasing = static_cast<render::Antialiasing>(state.range(0));
  render::HeadlessRenderer renderer(settings);
  render::Scene scene;
  if (with_splats) scene.point_sets.push_back(splats(100000));
  if (with_mesh) scene.meshes.push_back(sphere(125, 200));  // 50,000 triangles
  const render::Camera camera = render::fit_camera(scene.all_points(), render::View::iso, 1280.0 / 960.0);
  renderer.render(scene, camera);  // llvmpipe compiles its shader variants on the first draw
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(scene, camera));
  state.SetLabel(state.range(0) == 0   ? "msaa x4"
                 : state.range(0) == 1 ? "edge smoothing"
                                       : "no antialiasing");
}

void BM_SplatsAndMesh(benchmark::State& state) { frame(state, true, true); }
void BM_SplatsOnly(benchmark::State& state) { frame(state, true, false); }
void BM_MeshOnly(benchmark::State& state) { frame(state, false, true); }
void BM_Empty(benchmark::State& state) { frame(state, false, false); }

// Argument: the antialiasing (0 multisample x4, 1 edge smoothing, 2 none).
BENCHMARK(BM_SplatsAndMesh)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_SplatsOnly)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_MeshOnly)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_Empty)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
