// Normalisation round trips: apply then undo gives the input back, and the reference lands in a box of
// diagonal 1 centred at the origin.
#include "partreg/core/geometry/normalization.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

/// Points in an axis-aligned box of the given sides, offset from the origin (data units: think mm).
Points box_points(Eigen::Index count, const Eigen::RowVector3d& sides, const Eigen::RowVector3d& offset,
                  std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Points points(count, 3);
  for (Eigen::Index i = 0; i < count; ++i)
    for (int d = 0; d < 3; ++d) points(i, d) = offset[d] + sides[d] * uniform(generator);
  return points;
}

TEST(Normalization, ApplyThenUndoGivesTheInputBack) {
  const Points reference = box_points(500, {120.0, 40.0, 75.0}, {300.0, -80.0, 12.0}, 1);
  const Normalization normalization = Normalization::fit(reference);
  EXPECT_LT((normalization.undo(normalization.apply(reference)) - reference).cwiseAbs().maxCoeff(), 1e-12);

  // Other points through the same map, both ways round.
  const Points other = box_points(100, {500.0, 500.0, 500.0}, {-250.0, -250.0, -250.0}, 2);
  EXPECT_LT((normalization.undo(normalization.apply(other)) - other).cwiseAbs().maxCoeff(), 1e-12);
  const Points normalised = box_points(100, {2.0, 2.0, 2.0}, {-1.0, -1.0, -1.0}, 3);
  EXPECT_LT((normalization.apply(normalization.undo(normalised)) - normalised).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(normalization.to_data(normalization.to_normalised(42.5)), 42.5, 1e-12);
}

TEST(Normalization, TheReferenceGetsDiagonalOneAroundTheOrigin) {
  const Eigen::RowVector3d sides(120.0, 40.0, 75.0), offset(300.0, -80.0, 12.0);
  const Points reference = box_points(500, sides, offset, 4);
  const Normalization normalization = Normalization::fit(reference);
  const Points normalised = normalization.apply(reference);
  EXPECT_NEAR(bounding_box_diagonal(normalised), 1.0, 1e-12);
  const Eigen::RowVector3d centre = 0.5 * (normalised.colwise().minCoeff() + normalised.colwise().maxCoeff());
  EXPECT_LT(centre.norm(), 1e-12);
  // The factor is the data's own diagonal (close to the box's: 500 points nearly fill it).
  EXPECT_NEAR(normalization.scale, bounding_box_diagonal(reference), 1e-12 * normalization.scale);
  EXPECT_NEAR(normalization.scale, sides.norm(), 0.05 * sides.norm());
  EXPECT_NEAR(normalization.to_normalised(normalization.scale), 1.0, 1e-15);
}

TEST(Normalization, AFlatReferenceStillWorks) {
  // A planar set (z constant) has a box of zero height but a positive diagonal: it must normalise.
  Points flat = box_points(200, {3.0, 4.0, 0.0}, {1.0, 1.0, 7.0}, 5);
  const Normalization normalization = Normalization::fit(flat);
  EXPECT_NEAR(bounding_box_diagonal(normalization.apply(flat)), 1.0, 1e-12);
  EXPECT_LT((normalization.undo(normalization.apply(flat)) - flat).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Normalization, RefusesSetsItCannotScale) {
  EXPECT_THROW(Normalization::fit(Points(0, 3)), InputError);
  Points same(5, 3);
  same.rowwise() = Eigen::RowVector3d(1.0, 2.0, 3.0);
  EXPECT_THROW(Normalization::fit(same), InputError);
  Points with_nan = box_points(5, {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, 6);
  with_nan(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Normalization::fit(with_nan), InputError);
  with_nan(2, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(Normalization::fit(with_nan), InputError);
  EXPECT_THROW(bounding_box_diagonal(Points(0, 3)), InputError);
}

}  // namespace
}  // namespace partreg::core
