// Cameras, scenes, images and text without any GL.
#include "partreg/render/scene.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "partreg/core/errors.hpp"
#include "partreg/render/camera.hpp"
#include "partreg/render/image.hpp"
#include "partreg/render/text.hpp"
#include "render_scenes.hpp"

namespace partreg::render {
namespace {

Eigen::Vector3f to_ndc(const Camera& camera, double aspect, const Eigen::Vector3d& point) {
  const Eigen::Vector4f clip = camera.projection_matrix(aspect, 0.1, 100.0) * camera.view_matrix() *
                               Eigen::Vector4f(point.x(), point.y(), point.z(), 1.0f);
  return clip.head<3>() / clip.w();
}

TEST(Camera, TargetProjectsToTheCentreAndUpPointsUp) {
  Camera camera;
  camera.eye = Eigen::Vector3d(3.0, 1.0, 2.0);
  camera.target = Eigen::Vector3d(0.5, 0.2, -0.1);
  const Eigen::Vector3f centre = to_ndc(camera, 1.5, camera.target);
  EXPECT_NEAR(centre.x(), 0.0, 1e-5);
  EXPECT_NEAR(centre.y(), 0.0, 1e-5);
  EXPECT_GT(to_ndc(camera, 1.5, camera.target + 0.1 * Eigen::Vector3d::UnitY()).y(), 0.0);
}

TEST(Camera, NamedViewsLookFromTheirSide) {
  // +Y up, the front towards -Z.
  Bounds box;
  box.extend(Eigen::Vector3d(-1, -1, -1));
  box.extend(Eigen::Vector3d(1, 1, 1));
  EXPECT_LT(fit_camera(box, View::front, 1.0).eye.z(), -1.0);
  EXPECT_GT(fit_camera(box, View::side, 1.0).eye.x(), 1.0);
  const Camera top = fit_camera(box, View::top, 1.0);
  EXPECT_GT(top.eye.y(), 1.0);
  EXPECT_NO_THROW(top.view_matrix());  // straight above still has a usable up vector
  EXPECT_GT(top.up.z(), 0.9);          // the far side (+Z) up, the front at the bottom of the image
  const Camera iso = fit_camera(box, View::iso, 1.0);
  EXPECT_GT(iso.eye.x(), 1.0);
  EXPECT_GT(iso.eye.y(), 1.0);
  EXPECT_LT(iso.eye.z(), -1.0);
  // A wrong answer: the side view is not on the front's axis.
  EXPECT_LT(std::abs(fit_camera(box, View::side, 1.0).eye.z()), 1e-9);
}

TEST(Camera, FitKeepsEveryCornerInTheImage) {
  Bounds box;
  box.extend(Eigen::Vector3d(10, 20, -5));
  box.extend(Eigen::Vector3d(12, 21, 3));
  for (double aspect : {0.5, 1.0, 2.0})
    for (View view : {View::front, View::side, View::top, View::iso}) {
      const Camera camera = fit_camera(box, view, aspect);
      for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3d point((corner & 1) ? box.max.x() : box.min.x(),
                                    (corner & 2) ? box.max.y() : box.min.y(),
                                    (corner & 4) ? box.max.z() : box.min.z());
        const Eigen::Vector3f ndc = to_ndc(camera, aspect, point);
        EXPECT_LE(std::abs(ndc.x()), 1.0f);
        EXPECT_LE(std::abs(ndc.y()), 1.0f);
      }
    }
}

TEST(Camera, BadCamerasAndNamesAreUsageErrors) {
  Camera camera;
  camera.eye = camera.target;
  EXPECT_THROW(camera.view_matrix(), UsageError);
  camera.eye = Eigen::Vector3d(0, 2, 0);
  camera.up = Eigen::Vector3d::UnitY();
  EXPECT_THROW(camera.view_matrix(), UsageError);
  EXPECT_THROW(core::parse_enum<render::View>("diagonal"), UsageError);
}

TEST(Scene, BoundsAndEmptiness) {
  Scene scene;
  EXPECT_TRUE(scene.empty());
  EXPECT_TRUE(scene.bounds().empty());
  scene.line_sets.push_back(make_triad(Eigen::Vector3d(1, 2, 3), Eigen::Matrix3d::Identity(), 0.5));
  EXPECT_FALSE(scene.empty());
  EXPECT_TRUE(scene.bounds().max.isApprox(Eigen::Vector3d(1.5, 2.5, 3.5)));
  EXPECT_THROW(make_correspondences(core::Points(2, 3), core::Points(3, 3), Color::Zero()), UsageError);
}

TEST(Scene, VertexNormalsPointOutOfASphere) {
  const core::Mesh sphere = testing::uv_sphere(2.0, 12, 24);
  const core::Points normals = vertex_normals(sphere);
  for (Eigen::Index i = 0; i < normals.rows(); ++i)
    EXPECT_GT(normals.row(i).dot(sphere.vertices.row(i).normalized()), 0.95) << i;
}

TEST(Scene, VertexNormalsOfADoubleSidedMeshDoNotCancel) {
  // Every face twice, once per winding, on shared vertices (as ShapeNet exports often are).
  core::Mesh sphere = testing::uv_sphere(1.0, 12, 24);
  const Eigen::Index count = sphere.faces.rows();
  sphere.faces.conservativeResize(2 * count, 3);
  for (Eigen::Index f = 0; f < count; ++f)
    sphere.faces.row(count + f) << sphere.faces(f, 0), sphere.faces(f, 2), sphere.faces(f, 1);
  const core::Points normals = vertex_normals(sphere);
  for (Eigen::Index i = 0; i < normals.rows(); ++i)
    EXPECT_GT(std::abs(normals.row(i).dot(sphere.vertices.row(i).normalized())), 0.95) << i;
}

TEST(Scene, PartColoursComeFromTheLabelPalette) {
  Eigen::VectorXi part(3);
  part << 0, 1, -1;
  const Colors colors = part_colors(part);
  EXPECT_TRUE(colors.row(0).transpose().isApprox(part_color(0)));
  EXPECT_FALSE(colors.row(0).isApprox(colors.row(1)));
  EXPECT_TRUE(colors.row(2).transpose().isApprox(neutral_color()));
}

TEST(Image, BlitBlendsByAlphaAndClips) {
  Image canvas(4, 4, {255, 255, 255, 255});
  Image stamp(2, 2, {0, 0, 0, 255});
  stamp.pixel(1, 1)[3] = 0;
  blit(canvas, stamp, 3, 3);  // only stamp (0, 0) lands on the canvas
  EXPECT_EQ(canvas.pixel(3, 3)[0], 0);
  EXPECT_EQ(canvas.pixel(2, 2)[0], 255);
  blit(canvas, stamp, 0, 0);
  EXPECT_EQ(canvas.pixel(1, 1)[0], 255);  // transparent stamp pixel leaves the canvas as it was
}

TEST(Text, DrawsInsideItsWidth) {
  Image image(200, 40);
  draw_text(image, 5, 5, "hol+part", 2);
  int left = image.width, right = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.pixel(x, y)[0] == 0) left = std::min(left, x), right = std::max(right, x);
  EXPECT_EQ(left, 5);
  EXPECT_LE(right, 5 + text_width("hol+part", 2));
  EXPECT_GT(right, 5 + text_width("hol+part", 2) / 2);
}

}  // namespace
}  // namespace partreg::render
