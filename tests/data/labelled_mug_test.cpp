// The real mug model with parts (ShapeNet mugs, the committed labels of the canonical mug): its meshes
// stay whole across the seam between handle and body, and its handle has enough canonical points.
#include <gtest/gtest.h>

#include "partreg/core/registration/space_walk.hpp"
#include "support/labelled_mugs.hpp"

namespace partreg {
namespace {

constexpr double kStretchLimit = 3.0;  // no mesh edge beyond 3x its canonical length

double largest(const std::vector<core::SpaceStretch>& figures, const std::string& space) {
  double stretch = 0.0;
  for (const core::SpaceStretch& figure : figures)
    if (space.empty() || figure.space == space) stretch = std::max(stretch, figure.max_stretch);
  return stretch;
}

// Training takes about 25 s, so one test checks both the handle's points and the meshes' stretch.
TEST(LabelledMug, HandleHasItsFloorOfPointsAndBlendedMeshesDoNotTear) {
  PARTREG_REQUIRE_SHARED_DATA(testing::shared_data("mugs"));
  const core::CategoryModel model = testing::train_labelled_mugs();
  ASSERT_TRUE(model.has_parts());
  // Sampling the whole mug gives its handle 53 of 1000 points; the floor per part gives it 150.
  EXPECT_EQ(model.space("handle").point_count(), 150);
  EXPECT_EQ(model.training.min_part_points, 150);
  const auto blended = core::space_grid_stretch(model, {-2.0, 2.0});
  const auto torn = core::space_grid_stretch(model, {-2.0, 2.0}, core::SeamBlend{0.0});
  for (const core::SpaceStretch& figure : blended)
    std::cerr << "space " << figure.space << ": largest edge stretch " << figure.max_stretch << " (PC"
              << figure.direction + 1 << " at " << figure.std_devs << " sd), unblended "
              << largest(torn, figure.space) << "\n";
  // The part spaces' walks (the other part at its mean) stay within the limit. The holistic space's own
  // walk reaches 3.55x at -2 sd of PC2, as the training mugs' own CPD fits do (up to 3.5x): no seam there.
  EXPECT_LT(largest(blended, "body"), kStretchLimit);
  EXPECT_LT(largest(blended, "handle"), kStretchLimit);
  // Each part moved by its own field alone (the deformation before blending) tears the handle's seam.
  EXPECT_GT(largest(torn, "handle"), kStretchLimit);
}

}  // namespace
}  // namespace partreg
