// The desktop app's interactive costs, headless (OSMesa llvmpipe) at 1280x800 on canonical meshes of about
// 37,000 and 148,000 vertices: a shape-slider move (re-deform by Eq. 4 and redraw, panels included) and a
// paint stroke event. Targets: at least 30 frames per second while dragging a slider; under 30 ms
// per stroke event.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <map>

#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/render/mesh_proxy.hpp"
#include "partreg/render/osmesa_context.hpp"
#ifdef PARTREG_BENCH_HAS_WINDOW
#include "partreg/render/glfw_context.hpp"
#endif
#include "partreg/ui/executor.hpp"
#include "partreg/ui/gui_frame.hpp"
#include "partreg/ui/scene_builder.hpp"
#include "ui/ui_fixtures.hpp"

namespace partreg {
namespace {

// Splits every triangle into four (a vertex per edge midpoint) `times` times; new vertices take the part
// of the edge's first vertex.
void subdivide(core::Mesh& mesh, Eigen::VectorXi& vertex_part, int times) {
  for (int round = 0; round < times; ++round) {
    std::vector<Eigen::RowVector3d> vertices(mesh.vertices.rows());
    for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) vertices[i] = mesh.vertices.row(i);
    std::vector<int> parts(vertex_part.data(), vertex_part.data() + vertex_part.size());
    std::map<std::pair<int, int>, int> midpoint_of;
    auto midpoint = [&](int a, int b) {
      auto [found, inserted] = midpoint_of.try_emplace(std::minmax(a, b), static_cast<int>(vertices.size()));
      if (inserted) {
        vertices.push_back((vertices[a] + vertices[b]) / 2);
        parts.push_back(parts[a]);
      }
      return found->second;
    };
    core::Faces faces(4 * mesh.faces.rows(), 3);
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
      const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      faces.row(4 * f) << a, ab, ca;
      faces.row(4 * f + 1) << b, bc, ab;
      faces.row(4 * f + 2) << c, ca, bc;
      faces.row(4 * f + 3) << ab, bc, ca;
    }
    mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
    for (std::size_t i = 0; i < vertices.size(); ++i)
      mesh.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i];
    mesh.faces = faces;
    mesh.normals.resize(0, 3);
    vertex_part = Eigen::Map<Eigen::VectorXi>(parts.data(), static_cast<Eigen::Index>(parts.size()));
  }
}

// A synthetic mug model (M = 1000, q = 5) whose canonical mesh (about 2,450 vertices) is subdivided
// `times` times (twice: about 37,000 vertices; three times: about 148,000). The target (50,000) lies between.
std::filesystem::path dense_model_path(int times) {
  const std::string name = "dense_mug_" + std::to_string(times);
  const std::filesystem::path path = testing::ui_fixture_folder() / (name + ".prm");
  if (std::filesystem::exists(path)) return path;
  std::vector<core::TrainingInstance> instances;
  for (int i = 0; i < 6; ++i) {
    const core::SyntheticInstance mug = core::make_synthetic_instance(core::SyntheticCategory::mug, 7, i);
    const core::SurfaceSamples samples =
        core::sample_correspondences(core::SyntheticCategory::mug, mug.shape_parameters, 3000, 3);
    instances.push_back({mug.name, samples.points, samples.part, {}, {}});
    instances.back().mesh = testing::merged_mug(i, nullptr, &instances.back().mesh_vertex_part);
  }
  core::TrainingSettings settings;
  settings.canonical = instances.front().name;
  core::CategoryModel model =
      core::train_category("mugs", instances, core::part_names(core::SyntheticCategory::mug), settings);
  subdivide(model.canonical_mesh, model.mesh_vertex_part, times);
  io::write_model(path, model);
  io::write_mesh(testing::ui_fixture_folder() / (name + ".obj"), model.canonical_mesh);
  return path;
}

// range(0): subdivisions of the mesh; range(1): 0 = 4x multisampling (the app's default) at full quality,
// 1 = the same renderer drawing interactive frames (one sample per pixel: what the window draws while a
// slider is dragged), 2 = no antialiasing at all.
void BM_ShapeSliderFrame(benchmark::State& bench) {
  render::OsMesaContext context;
  ui::AppState state;
  state.viewport.width = 1280, state.viewport.height = 800;
  ui::execute(state, ui::make_command("load", {dense_model_path(static_cast<int>(bench.range(0))).string()}));
  const auto quality = bench.range(1) == 1 ? render::FrameQuality::interactive : render::FrameQuality::full;
  ui::GuiFrame frame(state.viewport,
                     bench.range(1) == 2 ? render::Antialiasing::none : render::Antialiasing::multisample);
  std::vector<ui::Command> ignored;
  frame.draw(state, 1.0 / 60, ignored, quality);  // builds the interactive proxy (BM_MeshProxyBuild)
  int tick = 0;
  for (auto _ : bench) {
    const std::string value = std::to_string(-2.0 + 0.1 * (tick++ % 40));
    ui::execute(state, ui::make_command("set_latent", {"holistic", "1", value}));
    frame.draw(state, 1.0 / 60, ignored, quality);
    benchmark::DoNotOptimize(frame.read_pixels());  // waits for llvmpipe to finish the frame
  }
  bench.counters["vertices"] = static_cast<double>(state.shapes.model->canonical_mesh.vertices.rows());
}
BENCHMARK(BM_ShapeSliderFrame)
    ->ArgsProduct({{2, 3}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

#ifdef PARTREG_BENCH_HAS_WINDOW
// The same slider move in the real window (GLFW, needs a display: `xvfb-run -a gui_benchmark`), shown the way
// the app shows it: drawn, blitted to the window, swapped. range(0): subdivisions; range(1): 0 = full quality
// (4x multisampling), 1 = interactive (what the window draws while the slider is dragged).
void BM_ShapeSliderWindowFrame(benchmark::State& bench) {
  if (!std::getenv("DISPLAY")) {
    bench.SkipWithError("needs a display: run under xvfb-run -a");
    return;
  }
  ui::AppState state;
  state.viewport.width = 1280, state.viewport.height = 800;
  // One window for every run: GLFW under Xvfb refuses a third window after two were closed.
  static render::GlfwContext context(state.viewport.width, state.viewport.height, "gui_benchmark");
  context.make_current();
  ui::execute(state, ui::make_command("load", {dense_model_path(static_cast<int>(bench.range(0))).string()}));
  ui::GuiFrame frame(state.viewport);
  const auto quality = bench.range(1) == 1 ? render::FrameQuality::interactive : render::FrameQuality::full;
  std::vector<ui::Command> ignored;
  frame.draw(state, 1.0 / 60, ignored, quality);
  int tick = 0;
  for (auto _ : bench) {
    const std::string value = std::to_string(-2.0 + 0.1 * (tick++ % 40));
    ui::execute(state, ui::make_command("set_latent", {"holistic", "1", value}));
    frame.draw(state, 1.0 / 60, ignored, quality);
    context.present(frame.framebuffer(), frame.width(), frame.height());
  }
  bench.counters["vertices"] = static_cast<double>(state.shapes.model->canonical_mesh.vertices.rows());
}
BENCHMARK(BM_ShapeSliderWindowFrame)
    ->ArgsProduct({{2, 3}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
#endif

// The CPU share of a slider frame: re-deform by Eq. 4 and build the scene the renderer draws (no GL).
void BM_ShapeSliderScene(benchmark::State& bench) {
  ui::AppState state;
  state.viewport.width = 1280, state.viewport.height = 800;
  ui::execute(state, ui::make_command("load", {dense_model_path(static_cast<int>(bench.range(0))).string()}));
  int tick = 0;
  for (auto _ : bench) {
    const std::string value = std::to_string(-2.0 + 0.1 * (tick++ % 40));
    ui::execute(state, ui::make_command("set_latent", {"holistic", "1", value}));
    benchmark::DoNotOptimize(ui::build_scene(state));
  }
}
BENCHMARK(BM_ShapeSliderScene)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

// The proxy an interactive frame draws for a dense mesh is built on the first such frame (the first slider
// drag after loading a model): a one-off pause of this length.
void BM_MeshProxyBuild(benchmark::State& bench) {
  const core::CategoryModel model = io::read_model(dense_model_path(static_cast<int>(bench.range(0))));
  for (auto _ : bench)
    benchmark::DoNotOptimize(
        render::MeshProxy(model.canonical_mesh, render::RenderSettings().interactive_triangles));
  bench.counters["vertices"] = static_cast<double>(model.canonical_mesh.vertices.rows());
}
BENCHMARK(BM_MeshProxyBuild)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PaintStroke(benchmark::State& bench) {
  const int times = static_cast<int>(bench.range(0));
  dense_model_path(times);
  ui::AppState state;
  state.viewport.width = 1280, state.viewport.height = 800;
  const std::string mesh = "dense_mug_" + std::to_string(times) + ".obj";
  ui::execute(state, ui::make_command("load", {(testing::ui_fixture_folder() / mesh).string()}));
  ui::execute(state, ui::make_command("create_part", {"handle"}));
  ui::execute(state, ui::make_command("camera", {"side"}));
  ui::execute(state, ui::make_command("paint", {"700", "400"}, {{"radius", "20"}}));  // builds the adjacency
  int tick = 0;
  for (auto _ : bench) {  // strokes across the middle of the mug (the labelling state only; no drawing)
    const int x = 700 + 4 * (tick++ % 50);
    ui::execute(state, ui::make_command("paint", {std::to_string(x), "400"}, {{"radius", "20"}}));
  }
  bench.counters["faces"] = static_cast<double>(state.labelling.mesh.faces.rows());
}
BENCHMARK(BM_PaintStroke)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace partreg

BENCHMARK_MAIN();
