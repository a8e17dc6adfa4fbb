#include "partreg/core/metrics.hpp"

#include <gtest/gtest.h>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

TEST(Metrics, Eq5AndChamferOnHandMadeSets) {
  Points truth(3, 3);
  truth << 0, 0, 0, 1, 0, 0, 0, 2, 0;
  Points deformed(2, 3);
  deformed << 0, 0, 0.5, 1, 0.5, 0;  // squared distances to the closest truth point: 0.25 and 0.25
  EXPECT_DOUBLE_EQ(closest_point_error(deformed, truth), 0.25);
  // deformed -> truth: 0.5, 0.5; truth -> deformed: 0.5, 0.5, |(0,2,0)-(1,0.5,0)| = sqrt(3.25)
  EXPECT_NEAR(chamfer_distance(deformed, truth), 0.5 * (0.5 + (1.0 + std::sqrt(3.25)) / 3.0), 1e-12);
  EXPECT_THROW(closest_point_error(Points(0, 3), truth), InputError);
}

}  // namespace
}  // namespace partreg::core
