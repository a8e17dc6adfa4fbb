// The renderer through OSMesa: known scenes at a fixed size and camera against the PNG baselines in
// tests/baselines (see image_baseline.hpp for the tolerance and where failures are written), and the
// failures that must come out as one clear line.
#include <gtest/gtest.h>

#include "image_baseline.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/render/figure.hpp"
#include "partreg/render/headless.hpp"
#include "partreg/render/text.hpp"
#include "render_scenes.hpp"
#include "support/temp_dir.hpp"

namespace partreg::render {
namespace {

using testing::expect_matches_baseline;

constexpr int kWidth = 320, kHeight = 240;

RenderSettings small(Background background = Background::white) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.background = background;
  return settings;
}

Scene mug_scene() {
  Eigen::VectorXi part;
  PointSet mug;
  mug.positions = testing::mug_points(part);
  mug.colors = part_colors(part);
  Scene scene;
  scene.point_sets.push_back(mug);
  return scene;
}

// Share of pixels that are not the background.
double covered_fraction(const Image& image, Rgba8 background = {255, 255, 255, 255}) {
  std::size_t covered = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!std::equal(background.begin(), background.end(), image.pixel(x, y))) ++covered;
  return static_cast<double>(covered) / (image.width * image.height);
}

TEST(Renderer, SplatsColouredByPartFromEachNamedView) {
  HeadlessRenderer renderer(small());
  const Scene scene = mug_scene();
  for (const char* view : {"iso", "front", "side", "top"}) {
    const Image image = renderer.render(scene, core::parse_enum<render::View>(view));
    EXPECT_GT(covered_fraction(image), 0.05) << view;
    expect_matches_baseline(image, std::string("splats_mug_parts_") + view);
  }
}

TEST(Renderer, BaselineComparisonCatchesAWrongPicture) {
  // The tolerance that passes the tests above must fail a picture of the wrong view or the wrong colours.
  HeadlessRenderer renderer(small());
  const Image front = read_png(testing::baseline_path("splats_mug_parts_front"));
  EXPECT_GT(testing::bad_pixel_fraction(renderer.render(mug_scene(), View::iso), front, 24), 0.05);
  Scene grey = mug_scene();
  grey.point_sets[0].colors.resize(0, 3);
  EXPECT_GT(testing::bad_pixel_fraction(renderer.render(grey, View::front), front, 24), 0.05);
}

TEST(Renderer, ExplicitCameraLooksFromWhereItIsTold) {
  HeadlessRenderer renderer(small());
  Camera camera;
  camera.eye = Eigen::Vector3d(0.0, -2.5, 2.5);  // from below the front: the bottom disc shows
  camera.target = Eigen::Vector3d::Zero();
  camera.up = Eigen::Vector3d::UnitY();
  expect_matches_baseline(renderer.render(mug_scene(), camera), "splats_mug_parts_from_below");
}

TEST(Renderer, SmoothMeshWithVertexColours) {
  HeadlessRenderer renderer(small());
  MeshItem sphere;
  sphere.mesh = testing::uv_sphere(1.0, 24, 48);
  Eigen::VectorXi part(sphere.mesh.vertices.rows());
  for (Eigen::Index i = 0; i < part.size(); ++i) part[i] = sphere.mesh.vertices(i, 1) > 0.0 ? 0 : 1;
  sphere.vertex_colors = part_colors(part);
  Scene scene;
  scene.meshes.push_back(sphere);
  expect_matches_baseline(renderer.render(scene, View::front), "mesh_sphere_smooth_two_colours_front");
}

TEST(Renderer, FlatMeshWithWireframe) {
  HeadlessRenderer renderer(small());
  MeshItem sphere;
  sphere.mesh = testing::uv_sphere(1.0, 6, 10);
  sphere.shading = Shading::flat;
  sphere.wireframe = true;
  sphere.color = part_color(2);
  Scene scene;
  scene.meshes.push_back(sphere);
  expect_matches_baseline(renderer.render(scene, View::iso), "mesh_sphere_flat_wireframe_iso");
}

TEST(Renderer, OpenMeshIsLitInsideAndOut) {
  HeadlessRenderer renderer(small());
  MeshItem cylinder;
  cylinder.mesh = testing::open_cylinder(0.5, 1.0, 64);
  cylinder.color = part_color(1);
  Scene scene;
  scene.meshes.push_back(cylinder);
  Camera camera;
  camera.eye = Eigen::Vector3d(0.0, 2.4, 1.4);  // steeply from above the front: most of the inside shows
  const Image image = renderer.render(scene, camera);
  expect_matches_baseline(image, "mesh_open_cylinder_two_sided_from_above");
  // The inner wall (seen through the open top, just above the centre) is lit, not black.
  const std::uint8_t* inside = image.pixel(kWidth / 2, kHeight / 2 - 10);
  EXPECT_GT(inside[0] + inside[1] + inside[2], 3 * 60);
}

TEST(Renderer, TriadAndCorrespondenceLines) {
  HeadlessRenderer renderer(small());
  core::Points from(8, 3), to(8, 3);
  for (int i = 0; i < 8; ++i) {
    from.row(i) << -1.0, 0.25 * i - 0.9, 0.0;
    to.row(i) << 1.0, 0.2 * i - 0.6, 0.3;
  }
  Scene scene;
  scene.line_sets.push_back(make_correspondences(from, to, Color(0.4f, 0.4f, 0.4f), 1.5f));
  scene.line_sets.push_back(
      make_triad(Eigen::Vector3d(0.0, -0.9, 0.0), Eigen::Matrix3d::Identity(), 0.6, 4.0f));
  PointSet ends;
  ends.positions.resize(16, 3);
  ends.positions << from, to;
  ends.color = observed_color();
  ends.radius = 0.04;
  scene.point_sets.push_back(ends);
  expect_matches_baseline(renderer.render(scene, View::front), "lines_triad_correspondences_front");
}

TEST(Renderer, TransparentBackground) {
  HeadlessRenderer renderer(small(Background::transparent));
  MeshItem sphere;
  sphere.mesh = testing::uv_sphere(1.0, 24, 48);
  sphere.color = part_color(0);
  Scene scene;
  scene.meshes.push_back(sphere);
  const Image image = renderer.render(scene, View::front);
  EXPECT_EQ(image.pixel(0, 0)[3], 0);
  EXPECT_EQ(image.pixel(kWidth / 2, kHeight / 2)[3], 255);
  expect_matches_baseline(image, "mesh_sphere_transparent_background");
}

TEST(Renderer, AntialiasingSoftensEdges) {
  // On a transparent background a silhouette without antialiasing is all-or-nothing in alpha; with either
  // kind, the rim pixels are partly covered.
  MeshItem sphere;
  sphere.mesh = testing::uv_sphere(1.0, 24, 48);
  Scene scene;
  scene.meshes.push_back(sphere);
  const auto partly_covered = [&](Antialiasing antialiasing) {
    RenderSettings settings = small(Background::transparent);
    settings.antialiasing = antialiasing;
    HeadlessRenderer renderer(settings);
    const Image image = renderer.render(scene, View::front);
    int count = 0;
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) count += image.rgba[i] > 0 && image.rgba[i] < 255;
    return count;
  };
  EXPECT_EQ(partly_covered(Antialiasing::none), 0);
  EXPECT_GT(partly_covered(Antialiasing::multisample), 100);
  EXPECT_GT(partly_covered(Antialiasing::edge), 100);
}

TEST(Renderer, InteractiveFramesAreACheaperLikenessOfTheFullOne) {
  // Drawn at half the size without multisampling and scaled up: not the same pixels, but the same picture,
  // and the next full-quality frame is exactly the full one again.
  MeshItem sphere;
  sphere.mesh = testing::uv_sphere(1.0, 24, 48);
  sphere.color = part_color(1);
  Scene scene;
  scene.meshes.push_back(sphere);
  scene.line_sets.push_back(make_triad(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), 1.5));
  OsMesaContext context;
  Renderer renderer(small());
  const Camera camera = fit_camera(scene.bounds(), View::iso, double(kWidth) / kHeight);
  testing::expect_interactive_likeness(renderer, scene, camera, 0.03);
}

TEST(Renderer, MeshesChangedBetweenFramesLookAsIfDrawnAfresh) {
  // The renderer keeps each mesh's buffers from the last frame and sends only what changed: whatever
  // changes (vertices, faces, colours, the number of meshes), the frame must equal a new renderer's.
  const auto sphere = [](double radius, int rings, const Color& color) {
    MeshItem item;
    item.mesh = testing::uv_sphere(radius, rings, 2 * rings);
    item.color = color;
    return item;
  };
  Scene first;
  first.meshes = {sphere(1.0, 12, part_color(0)), sphere(0.5, 8, part_color(1))};
  first.meshes[1].mesh.vertices.col(0).array() += 1.5;
  Scene second = first;
  second.meshes[0].mesh.vertices *= 0.8;  // a slider move
  second.meshes[1].vertex_colors =
      part_colors(Eigen::VectorXi::Constant(second.meshes[1].mesh.vertices.rows(), 3));  // recoloured
  second.meshes.push_back(sphere(0.3, 6, part_color(4)));                                // one more
  second.meshes[2].mesh.vertices.col(1).array() += 1.2;
  Scene third = second;
  third.meshes[0] = sphere(0.9, 16, part_color(0));  // new faces
  third.meshes.pop_back();
  OsMesaContext context;
  Renderer kept(small());
  const Camera camera = fit_camera(second.bounds(), View::iso, double(kWidth) / kHeight);
  for (const Scene* scene : {&first, &second, &third, &first}) {
    const Image reused = kept.render(*scene, camera);
    Renderer fresh(small());
    const Image expected = fresh.render(*scene, camera);
    EXPECT_EQ(reused.rgba, expected.rgba) << "scene with " << scene->meshes.size() << " meshes";
  }
}

TEST(Renderer, EdgeSmoothedSplatsAndMesh) {
  RenderSettings settings = small();
  settings.antialiasing = Antialiasing::edge;
  HeadlessRenderer renderer(settings);
  Scene scene = mug_scene();
  MeshItem sphere;
  sphere.mesh = testing::uv_sphere(0.3, 16, 32, Eigen::Vector3d(-0.9, 0.0, 0.0));
  sphere.color = part_color(2);
  scene.meshes.push_back(sphere);
  expect_matches_baseline(renderer.render(scene, View::front), "edge_smoothed_mug_and_sphere_front");
}

TEST(Renderer, EmptySceneIsBlankWithAWarning) {
  HeadlessRenderer renderer(small());
  ::testing::internal::CaptureStderr();
  const Image image = renderer.render(Scene(), View::iso);
  const std::string warning = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warning.find("warning"), std::string::npos);
  EXPECT_EQ(covered_fraction(image), 0.0);
}

TEST(Figure, GridWithTitlesAndLabels) {
  // Two rows (mug, sphere) by two columns (front, the same shape in grey), one shared camera.
  Grid grid;
  grid.columns = 2;
  grid.row_labels = {"mug", "ball"};
  grid.column_labels = {"parts", "grey"};
  Scene grey_mug = mug_scene();
  grey_mug.point_sets[0].colors.resize(0, 3);
  Scene ball;
  MeshItem sphere;
  sphere.mesh = testing::uv_sphere(0.5, 16, 32);
  sphere.color = part_color(2);
  ball.meshes.push_back(sphere);
  Scene grey_ball = ball;
  grey_ball.meshes[0].color = neutral_color();
  grid.panels = {{"A", mug_scene()}, {"B", grey_mug}, {"C", ball}, {"D", grey_ball}};
  FigureSettings settings;
  settings.panel_width = 200;
  settings.panel_height = 150;
  settings.view = View::front;
  const Image figure = render_grid(grid, settings);
  EXPECT_EQ(figure.height, text_line_height(2) + 8 + 2 * 150 + 8);
  expect_matches_baseline(figure, "figure_grid_titles_labels_front");
}

TEST(Renderer, ShaderThatDoesNotCompileIsOneClearLine) {
  OsMesaContext context;
  try {
    compile_program("broken", "void main() { gl_Position = vec4(0.0); }", "",
                    "out vec4 colour;\nvoid main() { colour = undefined_thing; }");
    FAIL() << "a broken shader compiled";
  } catch (const InputError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("shader broken (fragment) does not compile"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(Renderer, ImageSizeOutsideTheLimitsIsAUsageError) {
  RenderSettings settings = small();
  settings.width = 0;
  EXPECT_THROW(HeadlessRenderer{settings}, UsageError);
}

TEST(Renderer, UnwritableImageIsAnInputError) {
  const testing::TempDir folder;
  const Image image(4, 4);
  try {
    write_png(folder / "missing" / "out.png", image);
    FAIL() << "wrote into a missing folder";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("cannot write"), std::string::npos) << error.what();
  }
  write_png(folder / "out.png", image);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"out.png"});  // nothing half-written beside it
}

TEST(Renderer, PngRoundTrip) {
  const testing::TempDir folder;
  Image image(3, 2, {10, 20, 30, 255});
  image.pixel(2, 1)[3] = 0;
  write_png(folder / "round.png", image);
  const Image back = read_png(folder / "round.png");
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.rgba, image.rgba);
}

}  // namespace
}  // namespace partreg::render
