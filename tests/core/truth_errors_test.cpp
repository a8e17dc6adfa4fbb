#include "partreg/core/truth_errors.hpp"

#include <gtest/gtest.h>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

// The truth: three points, bounding box 1 x 2 x 0, so D = sqrt(5). Two deformed points.
struct HandMade {
  Points truth = (Points(3, 3) << 0, 0, 0, 1, 0, 0, 0, 2, 0).finished();
  Points deformed = (Points(2, 3) << 0, 0, 0.5, 1, 0.5, 0).finished();
  Eigen::VectorXi part = (Eigen::VectorXi(2) << 0, 1).finished();
};

TEST(TruthErrors, Eq5AndChamferOnHandMadeSets) {
  const HandMade set;
  // Squared distances to the closest truth point: 0.25 and 0.25.
  EXPECT_DOUBLE_EQ(closest_point_error(set.deformed, set.truth), 0.25);
  // deformed -> truth: 0.5, 0.5; truth -> deformed: 0.5, 0.5, |(0,2,0)-(1,0.5,0)| = sqrt(3.25)
  EXPECT_NEAR(chamfer_distance(set.deformed, set.truth), 0.5 * (0.5 + (1.0 + std::sqrt(3.25)) / 3.0), 1e-12);
  EXPECT_THROW(closest_point_error(Points(0, 3), set.truth), InputError);
}

TEST(TruthErrors, EveryFigureIsPinnedAndNormalisedByTheTruthsDiagonal) {
  const HandMade set;
  const double D = truth_diagonal(set.truth);
  ASSERT_DOUBLE_EQ(D, std::sqrt(5.0));  // the truth's box, not the deformed points' (whose diagonal is 1)
  const TruthErrors e = measure_against_truth(set.deformed, set.part, {"body", "handle"}, set.truth, D);
  EXPECT_DOUBLE_EQ(e.diagonal, D);
  EXPECT_DOUBLE_EQ(e.eq5, 0.25);
  EXPECT_DOUBLE_EQ(e.eq5_per_diagonal2, 0.25 / 5.0);
  // Reverse: truth points to their closest deformed point, squared: 0.25, 0.25, 3.25.
  EXPECT_DOUBLE_EQ(e.reverse_eq5, (0.25 + 0.25 + 3.25) / 3.0);
  EXPECT_NEAR(e.symmetric_rms_per_diagonal, 0.5 * (0.5 + std::sqrt(1.25)) / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(e.chamfer_per_diagonal, chamfer_distance(set.deformed, set.truth) / D, 1e-15);
  EXPECT_DOUBLE_EQ(e.part_eq5_per_diagonal2.at("body"), 0.25 / 5.0);
  EXPECT_DOUBLE_EQ(e.part_eq5_per_diagonal2.at("handle"), 0.25 / 5.0);
  EXPECT_FALSE(e.correspondence_per_diagonal);
}

TEST(TruthErrors, CorrespondenceAndBadInput) {
  const HandMade set;
  const Points truth_of_row = (Points(2, 3) << 0, 0, 0, 1, 0, 0).finished();
  const TruthErrors e =
      measure_against_truth(set.deformed, set.part, {"body", "handle"}, set.truth, 2.0, &truth_of_row);
  ASSERT_TRUE(e.correspondence_per_diagonal);
  EXPECT_DOUBLE_EQ(*e.correspondence_per_diagonal, 0.5 / 2.0);
  EXPECT_THROW(measure_against_truth(Points(0, 3), set.part, {}, set.truth, 1.0), InputError);
  EXPECT_THROW(measure_against_truth(set.deformed, set.part, {}, set.truth, 0.0), InputError);
  const Points wrong_rows = Points::Zero(3, 3);
  EXPECT_THROW(measure_against_truth(set.deformed, set.part, {}, set.truth, 1.0, &wrong_rows), InputError);
}

}  // namespace
}  // namespace partreg::core
