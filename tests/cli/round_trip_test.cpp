// What `register` writes, partreg reads back with the same information: parts by index and name, normals,
// each point's residual and the observed point it corresponds to, in .ply and .vtp; and `render --color-by
// part` draws the parts of either.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "partreg/io/cloud_io.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"
#include "support/run_partreg.hpp"
#include "support/temp_dir.hpp"
#ifdef PARTREG_HAS_RENDER
#include "partreg/render/image.hpp"
#endif

namespace partreg {
namespace {

using testing::Outcome;

class RoundTrip : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new testing::TempDir();
    ASSERT_EQ(testing::run_partreg("synth mug --out " + path("mugs") + " --instances 4 --seed 3").exit_code,
              0);
    ASSERT_EQ(testing::run_partreg("train " + path("mugs") + " --out " + path("mug.prm") + " --points 300")
                  .exit_code,
              0);
    // Both formats of both outputs, from one registration each (the same request: the same result).
    for (const char* format : {"ply", "vtp"}) {
      const Outcome registered = testing::run_partreg(
          "register " + path("mug.prm") + " " + observed_path() + " --variant hol+part" + " --points-out " +
          path(std::string("points.") + format) + " --mesh-out " + path(std::string("mesh.") + format));
      ASSERT_EQ(registered.exit_code, 0) << registered.output;
    }
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string path(const std::string& name) { return (*dir_ / name).string(); }
  static std::string observed_path() { return path("mugs/ground_truth/mug_003.ply"); }

  // Every point carries its part (a name of the model's) and its residual: the distance to the observed
  // point its correspondence names, in the observation as `register` read it (3000 samples, seed 1).
  static void expect_fit_attributes(const core::Points& points, const io::PointAttributes& attributes,
                                    double precision) {
    const core::CategoryModel model = io::read_model(path("mug.prm"));
    const core::Points observed = io::read_as_cloud(observed_path(), 3000, 1).points;
    EXPECT_EQ(attributes.part_names, model.part_names);
    ASSERT_EQ(model.part_names.size(), 2u);
    const Eigen::VectorXi& part = attributes.integers.at("part");
    const Eigen::VectorXi& correspondence = attributes.integers.at("correspondence");
    const Eigen::VectorXd& residual = attributes.reals.at("residual");
    ASSERT_EQ(part.size(), points.rows());
    EXPECT_EQ(part.minCoeff(), 0);
    EXPECT_EQ(part.maxCoeff(), 1);
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      ASSERT_TRUE(correspondence[i] >= 0 && correspondence[i] < observed.rows()) << i;
      EXPECT_NEAR((points.row(i) - observed.row(correspondence[i])).norm(), residual[i], precision) << i;
    }
    EXPECT_GT(residual.maxCoeff(),
              0.0);  // a residual of zeros would pass the loop above for matched points only
  }

  // Unit normals; a mesh's vertex on no face has none to give (zero), a point always has its nearest
  // vertex's on a face.
  static void expect_unit_normals(const core::Points& normals, Eigen::Index rows, bool zero_allowed = false) {
    ASSERT_EQ(normals.rows(), rows);
    for (Eigen::Index i = 0; i < rows; ++i) {
      const double length = normals.row(i).norm();
      if (zero_allowed && length == 0.0) continue;
      EXPECT_NEAR(length, 1.0, 1e-5) << i;
    }
  }

  static testing::TempDir* dir_;
};

testing::TempDir* RoundTrip::dir_ = nullptr;

TEST_F(RoundTrip, PointsCarryPartsNormalsResidualsAndCorrespondencesInPlyAndVtp) {
  const io::CloudFile ply = io::read_cloud_file(path("points.ply"));  // float32 coordinates
  const io::CloudFile vtp = io::read_cloud_file(path("points.vtp"));  // float64
  expect_fit_attributes(ply.cloud.points, ply.attributes, 1e-5);
  expect_fit_attributes(vtp.cloud.points, vtp.attributes, 1e-12);
  expect_unit_normals(ply.cloud.normals, ply.cloud.points.rows());
  expect_unit_normals(vtp.cloud.normals, vtp.cloud.points.rows());
  ASSERT_EQ(ply.cloud.points.rows(), vtp.cloud.points.rows());
  EXPECT_LT((ply.cloud.points - vtp.cloud.points).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_EQ(ply.attributes.integers.at("part"), vtp.attributes.integers.at("part"));
}

TEST_F(RoundTrip, MeshesCarryPartsNormalsResidualsAndCorrespondencesInPlyAndVtp) {
  const io::MeshFile ply = io::read_mesh_file(path("mesh.ply"));
  const io::MeshFile vtp = io::read_mesh_file(path("mesh.vtp"));
  expect_fit_attributes(ply.mesh.vertices, ply.vertex_attributes, 1e-6);
  expect_fit_attributes(vtp.mesh.vertices, vtp.vertex_attributes, 1e-12);
  expect_unit_normals(ply.mesh.normals, ply.mesh.vertices.rows(), /*zero_allowed=*/true);
  expect_unit_normals(vtp.mesh.normals, vtp.mesh.vertices.rows(), /*zero_allowed=*/true);
  // The model's own part per vertex, as the canonical mesh was labelled.
  const core::CategoryModel model = io::read_model(path("mug.prm"));
  EXPECT_EQ(vtp.vertex_attributes.integers.at("part"), model.mesh_vertex_part);
  EXPECT_EQ(vtp.mesh.faces, model.canonical_mesh.faces);
}

TEST_F(RoundTrip, RenderColoursTheParts) {
  for (const char* format : {"ply", "vtp"}) {
    const std::string mesh = path(std::string("mesh.") + format);
    const Outcome drawn = testing::run_partreg("render " + mesh + " --color-by part --size 160x120 --out " +
                                               path(std::string("parts_") + format + ".png"));
    ASSERT_EQ(drawn.exit_code, 0) << drawn.output;
    EXPECT_EQ(drawn.output.find("no part labels"), std::string::npos) << drawn.output;
  }
#ifdef PARTREG_HAS_RENDER
  // The .vtp mesh's parts draw as the .ply mesh's do, and not as the same mesh in grey.
  ASSERT_EQ(testing::run_partreg("render " + path("mesh.vtp") + " --color-by none --size 160x120 --out " +
                                 path("grey.png"))
                .exit_code,
            0);
  const render::Image vtp = render::read_png(path("parts_vtp.png")),
                      ply = render::read_png(path("parts_ply.png")),
                      grey = render::read_png(path("grey.png"));
  const auto differing = [](const render::Image& a, const render::Image& b) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4)
      count += std::abs(a.rgba[i] - b.rgba[i]) + std::abs(a.rgba[i + 1] - b.rgba[i + 1]) +
                   std::abs(a.rgba[i + 2] - b.rgba[i + 2]) >
               24;
    return count;
  };
  const std::size_t pixels = vtp.rgba.size() / 4;
  EXPECT_LT(differing(vtp, ply), pixels / 100);
  EXPECT_GT(differing(vtp, grey), pixels / 20);
#endif
}

}  // namespace
}  // namespace partreg
