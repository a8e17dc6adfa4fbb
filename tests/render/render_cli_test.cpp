// `partreg render` and `partreg figure` as a user runs them: images of the asked size showing the asked
// colours, and one clear line with the right exit code when something is wrong.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <set>

#include "partreg/io/cloud_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/render/image.hpp"
#include "partreg/render/palette.hpp"
#include "render_scenes.hpp"
#include "support/run_partreg.hpp"
#include "support/temp_dir.hpp"

namespace partreg {
namespace {

using testing::run_partreg;

// The number of output lines (a failure must be one line).
int lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

// How many pixels are within `tolerance` of `color` (ignoring shading: only hue-dominant pixels count when
// compared after normalising by the brightest channel).
int pixels_near(const render::Image& image, const render::Color& color, double tolerance = 0.12) {
  const Eigen::Vector3f target = color / color.maxCoeff();
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      const Eigen::Vector3f rgb(p[0], p[1], p[2]);
      if (rgb.maxCoeff() < 30.0f) continue;
      if ((rgb / rgb.maxCoeff() - target).cwiseAbs().maxCoeff() < tolerance) ++count;
    }
  return count;
}

// A mug cloud with a `part` attribute and a sphere mesh, written where the test can render them.
void write_inputs(const testing::TempDir& folder) {
  Eigen::VectorXi part;
  io::PointAttributes attributes;
  core::Cloud cloud{testing::mug_points(part), {}};
  attributes.integers["part"] = part;
  io::write_cloud_ply(folder / "mug.ply", cloud, attributes);
  io::write_mesh(folder / "sphere.obj", testing::uv_sphere(0.3, 16, 32, Eigen::Vector3d(-1.0, 0.0, 0.0)));
}

TEST(RenderCommand, DrawsFilesInTheAskedSizeAndColours) {
  const testing::TempDir folder;
  write_inputs(folder);
  const auto by_part =
      run_partreg("render " + (folder / "mug.ply").string() + " " + (folder / "sphere.obj").string() +
                  " --color-by part --size 400x300 --view front --out " + (folder / "parts.png").string());
  ASSERT_EQ(by_part.exit_code, 0) << by_part.output;
  const render::Image image = render::read_png(folder / "parts.png");
  EXPECT_EQ(image.width, 400);
  EXPECT_EQ(image.height, 300);
  // The mug's two parts in their palette colours; the sphere has no parts: grey.
  EXPECT_GT(pixels_near(image, render::part_color(0)), 1000);
  EXPECT_GT(pixels_near(image, render::part_color(1)), 200);
  EXPECT_GT(pixels_near(image, render::neutral_color(), 0.05), 1000);
  EXPECT_NE(by_part.output.find("sphere.obj has no part labels"), std::string::npos) << by_part.output;

  // By file: the first file in the first palette colour, the second in the second; no part colours.
  const auto by_file =
      run_partreg("render " + (folder / "sphere.obj").string() + " " + (folder / "mug.ply").string() +
                  " --size 400x300 --view front --out " + (folder / "files.png").string());
  ASSERT_EQ(by_file.exit_code, 0) << by_file.output;
  const render::Image files = render::read_png(folder / "files.png");
  EXPECT_GT(pixels_near(files, render::file_color(0)), 200);
  EXPECT_GT(pixels_near(files, render::file_color(1)), 1000);
  // A wrong answer: with --color-by none, no palette colour shows.
  const auto grey = run_partreg("render " + (folder / "mug.ply").string() +
                                " --color-by none --size 400x300 --out " + (folder / "grey.png").string());
  ASSERT_EQ(grey.exit_code, 0) << grey.output;
  EXPECT_EQ(pixels_near(render::read_png(folder / "grey.png"), render::part_color(1)), 0);
}

TEST(RenderCommand, EmptySceneIsABlankImageWithAWarning) {
  const testing::TempDir folder;
  const auto outcome = run_partreg("render --size 64x48 --out " + (folder / "blank.png").string());
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  EXPECT_NE(outcome.output.find("warning"), std::string::npos);
  const render::Image image = render::read_png(folder / "blank.png");
  EXPECT_EQ(std::set<std::uint8_t>(image.rgba.begin(), image.rgba.end()), std::set<std::uint8_t>{255});
}

TEST(RenderCommand, FailuresAreOneLineWithTheirExitCode) {
  const testing::TempDir folder;
  write_inputs(folder);
  const std::string mug = (folder / "mug.ply").string();
  const auto bad_size = run_partreg("render " + mug + " --size 12 --out " + (folder / "a.png").string());
  EXPECT_EQ(bad_size.exit_code, 2);
  EXPECT_EQ(lines(bad_size.output), 1) << bad_size.output;
  const auto bad_view =
      run_partreg("render " + mug + " --view diagonal --out " + (folder / "a.png").string());
  EXPECT_EQ(bad_view.exit_code, 2);
  const auto missing =
      run_partreg("render " + (folder / "none.ply").string() + " --out " + (folder / "a.png").string());
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(lines(missing.output), 1) << missing.output;
  const auto unwritable =
      run_partreg("render " + mug + " --size 64x48 --out " + (folder / "no" / "a.png").string());
  EXPECT_EQ(unwritable.exit_code, 1);
  EXPECT_NE(unwritable.output.find("partreg: cannot write"), std::string::npos) << unwritable.output;
  EXPECT_EQ(lines(unwritable.output), 1) << unwritable.output;  // refused before reading anything
  EXPECT_EQ(folder.entries().size(), 2u);                       // the inputs only: nothing half-written
}

TEST(RenderCommand, AContextThatCannotBeCreatedIsOneLine) {
  const testing::TempDir folder;
  write_inputs(folder);
  const std::string arguments =
      "render " + (folder / "mug.ply").string() + " --size 64x48 --out " + (folder / "a.png").string();
  // Mesa then offers at most OpenGL 2.1: no 3.3 core context.
  setenv("MESA_GL_VERSION_OVERRIDE", "2.1", 1);
  const auto old_gl = run_partreg(arguments);
  unsetenv("MESA_GL_VERSION_OVERRIDE");
  EXPECT_EQ(old_gl.exit_code, 1);
  EXPECT_NE(old_gl.output.find("partreg: cannot create an OSMesa OpenGL 3.3 core context"), std::string::npos)
      << old_gl.output;
  // A driver OSMesa lacks (Mesa itself would crash).
  setenv("GALLIUM_DRIVER", "zink", 1);
  const auto no_driver = run_partreg(arguments);
  unsetenv("GALLIUM_DRIVER");
  EXPECT_EQ(no_driver.exit_code, 1) << no_driver.output;
  EXPECT_NE(no_driver.output.find("GALLIUM_DRIVER=zink"), std::string::npos) << no_driver.output;
  EXPECT_FALSE(std::filesystem::exists(folder / "a.png"));
}

TEST(FigureCommand, CompareAndSpaceOnASmallSyntheticModel) {
  const testing::TempDir folder;
  const std::string mugs = (folder / "mugs").string(), model = (folder / "mugs.prm").string();
  ASSERT_EQ(run_partreg("synth mug --instances 4 --seed 2 --out " + mugs).exit_code, 0);
  const auto train = run_partreg("train " + mugs + " --out " + model + " --latent 2 --points 300");
  ASSERT_EQ(train.exit_code, 0) << train.output;
  const std::string observed = (folder / "mugs" / "ground_truth" / "mug_003.ply").string();

  const auto compare =
      run_partreg("figure compare " + model + " " + observed +
                  " --variants holistic,hol+part --size 320x180 --out " + (folder / "compare.png").string());
  ASSERT_EQ(compare.exit_code, 0) << compare.output;
  const render::Image figure = render::read_png(folder / "compare.png");
  EXPECT_EQ(figure.width, 2 * 320 + 8);  // two panels and the gap between them
  EXPECT_EQ(figure.height, 2 * 180 + 8);                          // side by side above, overlaid below
  EXPECT_GT(pixels_near(figure, render::observed_color()), 500);  // the observation in red
  EXPECT_GT(pixels_near(figure, render::part_color(1)), 100);     // the handle in its part colour

  const auto space = run_partreg("figure space " + model + " --space handle --size 160x120 --out " +
                                 (folder / "space.png").string());
  ASSERT_EQ(space.exit_code, 0) << space.output;
  const render::Image grid = render::read_png(folder / "space.png");
  EXPECT_GT(grid.width, 5 * 160);   // five columns and the row labels
  EXPECT_GT(grid.height, 2 * 120);  // two principal directions and the column labels

  const auto bad_variant = run_partreg("figure compare " + model + " " + observed +
                                       " --variants sideways --out " + (folder / "x.png").string());
  EXPECT_EQ(bad_variant.exit_code, 2);
  EXPECT_EQ(lines(bad_variant.output), 1) << bad_variant.output;
  const auto bad_space =
      run_partreg("figure space " + model + " --space lid --out " + (folder / "x.png").string());
  EXPECT_EQ(bad_space.exit_code, 2) << bad_space.output;
}

}  // namespace
}  // namespace partreg
