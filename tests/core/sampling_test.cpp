// Farthest-point sampling checked against its definition: starts at the given row, every next pick is a
// point farthest from the rows picked so far, no row twice, and exactly the count asked for.
#include "partreg/core/geometry/sampling.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <random>
#include <set>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

Points random_points(Eigen::Index count, std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Points points(count, 3);
  for (Eigen::Index i = 0; i < count; ++i)
    for (int d = 0; d < 3; ++d) points(i, d) = uniform(generator);
  return points;
}

/// Squared distance of every row of `points` to the nearest of the rows `picked`.
Eigen::VectorXd squared_distance_to(const Points& points, const std::vector<int>& picked) {
  Eigen::VectorXd distance =
      Eigen::VectorXd::Constant(points.rows(), std::numeric_limits<double>::infinity());
  for (const int row : picked)
    distance = distance.cwiseMin((points.rowwise() - points.row(row)).rowwise().squaredNorm());
  return distance;
}

/// Checks the definition pick by pick (a brute-force O(N count^2) scan; fine for test sizes).
void expect_farthest_point_order(const Points& points, const std::vector<int>& picks, int first) {
  ASSERT_FALSE(picks.empty());
  EXPECT_EQ(picks.front(), first);
  std::vector<int> so_far{picks.front()};
  for (std::size_t k = 1; k < picks.size(); ++k) {
    const Eigen::VectorXd distance = squared_distance_to(points, so_far);
    ASSERT_GE(picks[k], 0);
    ASSERT_LT(picks[k], points.rows());
    EXPECT_DOUBLE_EQ(distance[picks[k]], distance.maxCoeff()) << "pick " << k << " is not a farthest point";
    so_far.push_back(picks[k]);
  }
  EXPECT_EQ(std::set<int>(picks.begin(), picks.end()).size(), picks.size()) << "a row was picked twice";
}

TEST(FarthestPointSampling, EveryPickIsTheFarthestFromThoseBefore) {
  const Points points = random_points(600, 3);
  for (const int first : {0, 17, 599}) {
    SCOPED_TRACE("first row " + std::to_string(first));
    const std::vector<int> picks = farthest_point_indices(points, 60, first);
    ASSERT_EQ(picks.size(), 60u);
    expect_farthest_point_order(points, picks, first);
  }
}

/// The plain O(N count) loop the pruned sampler must reproduce exactly: ties to the lowest row.
std::vector<int> plain_farthest_points(const Points& points, std::size_t count, int first) {
  Eigen::VectorXd distance = Eigen::VectorXd::Constant(points.rows(), std::numeric_limits<double>::infinity());
  std::vector<int> picks{first};
  distance[first] = -1.0;
  while (picks.size() < count) {
    int farthest = -1;
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      if (distance[i] >= 0.0) distance[i] = std::min(distance[i], (points.row(i) - points.row(picks.back())).squaredNorm());
      if (farthest < 0 || distance[i] > distance[farthest]) farthest = static_cast<int>(i);
    }
    distance[farthest] = -1.0;
    picks.push_back(farthest);
  }
  return picks;
}

TEST(FarthestPointSampling, PicksWhatThePlainLoopPicksTiesAndDuplicatesIncluded) {
  // A regular grid (every distance ties with many others) with each point twice, and a random set.
  Points grid(2 * 512, 3);
  for (int i = 0; i < 512; ++i)
    grid.row(i) = grid.row(512 + i) = Eigen::RowVector3d(i % 8, (i / 8) % 8, i / 64);
  for (const auto& [points, first] : {std::pair{grid, 3}, std::pair{random_points(3000, 11), 0}}) {
    for (const std::size_t count : {std::size_t{1}, std::size_t{40}, std::size_t{700}, std::size_t(points.rows())})
      EXPECT_EQ(farthest_point_indices(points, count, first), plain_farthest_points(points, count, first))
          << count << " of " << points.rows();
  }
}

TEST(FarthestPointSampling, PicksTheCornersOfACubeFirst) {
  // Interior points plus the 8 corners: from the centre, the next 8 picks must be the 8 corners.
  Points points(108, 3);
  points.topRows(100) = 0.5 * random_points(100, 5);
  points.row(0).setZero();  // the start, at the centre
  for (int c = 0; c < 8; ++c) points.row(100 + c) << (c & 1 ? 1 : -1), (c & 2 ? 1 : -1), (c & 4 ? 1 : -1);
  const std::vector<int> picks = farthest_point_indices(points, 9, 0);
  EXPECT_EQ(std::set<int>(picks.begin() + 1, picks.end()),
            std::set<int>({100, 101, 102, 103, 104, 105, 106, 107}));
}

TEST(FarthestPointSampling, AllRowsAtTheSizeAndAnErrorAbove) {
  const Points points = random_points(50, 9);
  const std::vector<int> all = farthest_point_indices(points, 50, 4);
  ASSERT_EQ(all.size(), 50u);
  expect_farthest_point_order(points, all, 4);  // a permutation of every row
  EXPECT_THROW(farthest_point_indices(points, 51), InputError);
  EXPECT_TRUE(farthest_point_indices(points, 0).empty());
  EXPECT_THROW(farthest_point_indices(points, 5, 50), UsageError);
  EXPECT_THROW(farthest_point_indices(points, 5, -1), UsageError);
  Points with_nan = points;
  with_nan(7, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(farthest_point_indices(with_nan, 50), InputError);  // not a crash in the heap or the tree
}

/// 30 distinct points, each three times over.
Points tripled_points() {
  const Points distinct = random_points(30, 13);
  Points points(90, 3);
  for (int copy = 0; copy < 3; ++copy) points.middleRows(copy * 30, 30) = distinct;
  return points;
}

TEST(FarthestPointSampling, CoversEveryDistinctPositionOfDuplicatedPoints) {
  const Points points = tripled_points();
  const std::vector<int> thirty = farthest_point_indices(points, 30, 0);
  expect_farthest_point_order(points, thirty, 0);
  std::set<int> positions;  // the first 30 picks are the 30 distinct positions, one row each
  for (const int row : thirty) positions.insert(row % 30);
  EXPECT_EQ(positions.size(), 30u);
}

// Once every distinct position is picked, every distance left is 0: the duplicates follow, never a row
// picked before.
TEST(FarthestPointSampling, NoRowTwiceWhenTheDistinctPositionsRunOut) {
  const Points points = tripled_points();
  expect_farthest_point_order(points, farthest_point_indices(points, 90, 0), 0);
  expect_farthest_point_order(points, farthest_point_indices(points, 45, 7), 7);
}

// A sphere's surface, four times denser on one half, with uniform outliers in the box twice its size (the
// paper's 20%): every surface point has company, the outliers off the surface do not.
TEST(RowsWithNeighbours, LeaveOutUniformOutliersAndKeepASurfaceOfUnevenDensity) {
  std::mt19937_64 generator(5);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Points points(2400, 3);
  for (Eigen::Index i = 0; i < 2000; ++i) {
    Eigen::Vector3d p(normal(generator), normal(generator), normal(generator));
    if (i % 4 == 0) p.x() = std::abs(p.x());  // 25% on the x > 0 half, 75% on x < 0: three times as dense
    else p.x() = -std::abs(p.x());
    points.row(i) = 0.5 * p.normalized().transpose();
  }
  for (Eigen::Index i = 2000; i < 2400; ++i)
    points.row(i) = Eigen::RowVector3d(uniform(generator), uniform(generator), uniform(generator));
  const std::vector<int> kept = rows_with_neighbours(points, 2, 3.0);  // registration's choice
  const std::set<int> kept_set(kept.begin(), kept.end());
  int surface_kept = 0, outliers_off_surface = 0, outliers_kept = 0;
  for (Eigen::Index i = 0; i < 2000; ++i) surface_kept += kept_set.count(static_cast<int>(i));
  for (Eigen::Index i = 2000; i < 2400; ++i) {
    if (std::abs(points.row(i).norm() - 0.5) < 0.1) continue;  // on the surface: indistinguishable
    ++outliers_off_surface;
    outliers_kept += kept_set.count(static_cast<int>(i));
  }
  std::cerr << "surface kept " << surface_kept << " of 2000; outliers off it kept " << outliers_kept << " of "
            << outliers_off_surface << "\n";
  EXPECT_GE(surface_kept, 1995);  // 2000 measured: the thin half stays (four times thinner: 1992)
  EXPECT_LE(outliers_kept, outliers_off_surface / 20);  // 2 of 364 measured
  EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end()));
  EXPECT_EQ(rows_with_neighbours(points, 2, 0.0).size(), 2400u);  // 0: every row
  EXPECT_EQ(rows_with_neighbours(points.topRows(3), 2, 3.0).size(), 3u);  // too few to judge: every row
  EXPECT_EQ(rows_with_neighbours(Points::Zero(50, 3), 2, 3.0).size(), 50u);  // no spacing to judge by
}

TEST(SelectRows, CopiesTheListedRowsInOrder) {
  const Points points = random_points(10, 17);
  const Points picked = select_rows(points, {7, 2, 7});
  ASSERT_EQ(picked.rows(), 3);
  EXPECT_EQ(picked.row(0), points.row(7));
  EXPECT_EQ(picked.row(1), points.row(2));
  EXPECT_EQ(picked.row(2), points.row(7));
}

}  // namespace
}  // namespace partreg::core
