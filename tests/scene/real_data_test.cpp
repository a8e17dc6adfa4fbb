// The scene cut on a real stereo scan (../shared/data/scenes): the table is found, the mug standing on it is
// the object chosen, and its points are the mug's size.
#include <gtest/gtest.h>

#include "partreg/core/geometry/normalization.hpp"
#include "partreg/scene/scene_input.hpp"
#include "partreg/scene/segmentation.hpp"
#include "support/shared_data.hpp"

namespace partreg::scene {
namespace {

TEST(RealScan, TheTableIsRemovedAndTheMugOnItChosen) {
  const std::filesystem::path scan = testing::shared_data("scenes/table_scene_mug_stereo_textured.pcd");
  PARTREG_REQUIRE_SHARED_DATA(scan);
  const SceneCut cut = cut_scene(read_scene_cloud(scan));
  // The camera looks down at the table: its normal points up the image (-y) and back towards the camera (-z).
  EXPECT_LT(cut.up.y(), -0.5);
  EXPECT_LT(cut.up.z(), -0.3);
  EXPECT_GT(cut.plane[3], 0.3);  // the camera stands well above the table (m)
  // A mug is about a decimetre: the cut's extent is one, not the table's metre.
  const double extent = core::bounding_box_diagonal(cut.object.points);
  EXPECT_GT(extent, 0.07);
  EXPECT_LT(extent, 0.25);
  // It stands on the table: its lowest points are a couple of centimetres above it at most.
  double lowest = 1e9;
  for (Eigen::Index i = 0; i < cut.object.points.rows(); ++i)
    lowest = std::min(lowest, cut.plane.head<3>().dot(cut.object.points.row(i).transpose()) + cut.plane[3]);
  EXPECT_GT(lowest, 0.0);
  EXPECT_LT(lowest, 0.03);
}

}  // namespace
}  // namespace partreg::scene
