#include "partreg/core/geometry/truth_errors.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

// A kettle turned half a turn: the handle lies where the true spout is and the spout where the true handle
// is. Every point has a true point under it and the other way round, so the whole-truth figures are zero;
// only each part against its own part sees the turn.
TEST(TruthErrors, OwnPartFigureSeesPartsSwappedThatTheWholeTruthCannot) {
  const Points truth = (Points(4, 3) << 0, 0, 0, 1, 0, 0, 3, 0, 0, -2, 0, 0).finished();  // D = 5
  const Eigen::VectorXi truth_part = (Eigen::VectorXi(4) << 0, 0, 1, 2).finished();
  const Points turned = (Points(4, 3) << 0, 0, 0, 1, 0, 0, -2, 0, 0, 3, 0, 0).finished();
  const Eigen::VectorXi part = truth_part;  // body, body, handle, spout
  const std::vector<std::string> names = {"body", "handle", "spout"};
  const TruthErrors e = measure_against_truth(turned, part, names, truth, 5.0, nullptr, &truth_part);
  EXPECT_DOUBLE_EQ(e.symmetric_rms_per_diagonal, 0.0);
  EXPECT_DOUBLE_EQ(e.own_part_rms_per_diagonal.at("body"), 0.0);
  EXPECT_DOUBLE_EQ(e.own_part_rms_per_diagonal.at("handle"), 1.0);  // 5 apart both ways, / D
  EXPECT_DOUBLE_EQ(e.own_part_rms_per_diagonal.at("spout"), 1.0);
  ASSERT_TRUE(e.own_part_rms_mean_per_diagonal);
  EXPECT_DOUBLE_EQ(*e.own_part_rms_mean_per_diagonal, 2.0 / 3.0);  // each part counts once
  // In place, every part is on its own part.
  const TruthErrors in_place = measure_against_truth(truth, part, names, truth, 5.0, nullptr, &truth_part);
  EXPECT_DOUBLE_EQ(*in_place.own_part_rms_mean_per_diagonal, 0.0);
  // Without the truth's parts there is no own-part figure.
  EXPECT_TRUE(measure_against_truth(turned, part, names, truth, 5.0).own_part_rms_per_diagonal.empty());
  EXPECT_FALSE(measure_against_truth(turned, part, names, truth, 5.0).own_part_rms_mean_per_diagonal);
}

TEST(TruthErrors, OwnPartFigureLeavesOutAPartTheTruthLacksAndRefusesMismatchedLabels) {
  const Points truth = (Points(3, 3) << 0, 0, 0, 1, 0, 0, 3, 0, 0).finished();    // D = 3
  const Eigen::VectorXi truth_part = (Eigen::VectorXi(3) << 0, 0, 1).finished();  // no spout
  const Points deformed = (Points(3, 3) << 0, 0, 0, 1, 0, 0, 3, 0, 1.5).finished();
  const Eigen::VectorXi part = (Eigen::VectorXi(3) << 0, 2, 1).finished();
  const TruthErrors e =
      measure_against_truth(deformed, part, {"body", "handle", "spout"}, truth, 3.0, nullptr, &truth_part);
  EXPECT_EQ(e.own_part_rms_per_diagonal.size(), 2u);
  EXPECT_DOUBLE_EQ(e.own_part_rms_per_diagonal.at("handle"), 0.5);  // 1.5 both ways, / D
  // body: (0,0,0) on its own; the true (1,0,0) is 1 from it.
  EXPECT_DOUBLE_EQ(e.own_part_rms_per_diagonal.at("body"), 0.5 * (0.0 + std::sqrt(0.5)) / 3.0);
  const Eigen::VectorXi short_labels = (Eigen::VectorXi(2) << 0, 1).finished();
  EXPECT_THROW(
      measure_against_truth(deformed, part, {"body", "handle", "spout"}, truth, 3.0, nullptr, &short_labels),
      InputError);
}

}  // namespace
}  // namespace partreg::core
