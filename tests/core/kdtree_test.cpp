// The KD-tree against brute force: every answer (with and without a starting hint) must equal what scanning all points gives, on random
// clouds and on the degenerate sets registration meets (duplicates, a line, a plane, one point).
#include "partreg/core/geometry/kdtree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

Points random_points(Eigen::Index count, std::uint64_t seed, double half_width = 1.0) {
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> uniform(-half_width, half_width);
  Points points(count, 3);
  for (Eigen::Index i = 0; i < count; ++i)
    for (int d = 0; d < 3; ++d) points(i, d) = uniform(generator);
  return points;
}

double squared_distance(const Points& points, Eigen::Index row, const Eigen::Vector3d& query) {
  return (points.row(row).transpose() - query).squaredNorm();
}

double brute_nearest_squared(const Points& points, const Eigen::Vector3d& query) {
  return (points.rowwise() - query.transpose()).rowwise().squaredNorm().minCoeff();
}

/// Rows within `radius` of `query`, leaving out those within `margin` of the sphere itself (where the
/// tree's and the scan's round-off could disagree about the same point).
std::set<int> brute_within(const Points& points, const Eigen::Vector3d& query, double radius, double margin,
                           std::set<int>* on_boundary) {
  std::set<int> inside;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double distance = std::sqrt(squared_distance(points, i, query));
    if (std::abs(distance - radius) <= margin)
      on_boundary->insert(static_cast<int>(i));
    else if (distance < radius)
      inside.insert(static_cast<int>(i));
  }
  return inside;
}

/// Checks nearest, nearest_all, nearest_k and radius on every query against a scan of `points`.
/// Ties (duplicate points) may return any of the tied rows, so indices are checked by their distance.
void expect_matches_brute_force(const Points& points, const Points& queries, double radius) {
  const KdTree tree(points);
  ASSERT_EQ(tree.size(), points.rows());
  std::vector<int> all_index;
  Eigen::VectorXd all_squared;
  tree.nearest_all(queries, all_index, all_squared);
  ASSERT_EQ(all_index.size(), static_cast<std::size_t>(queries.rows()));
  ASSERT_EQ(all_squared.size(), queries.rows());
  for (Eigen::Index q = 0; q < queries.rows(); ++q) {
    SCOPED_TRACE("query " + std::to_string(q));
    const Eigen::Vector3d query = queries.row(q).transpose();
    const double best = brute_nearest_squared(points, query);
    const auto [index, squared] = tree.nearest(query);
    ASSERT_GE(index, 0);
    ASSERT_LT(index, points.rows());
    EXPECT_NEAR(squared, best, 1e-12);
    EXPECT_NEAR(squared_distance(points, index, query), best, 1e-12) << "the index is not a nearest row";
    EXPECT_NEAR(all_squared[q], best, 1e-12);
    // Starting from a hint, whichever: the nearest of its neighbours, the farthest row, the answer itself.
    for (const int hint : {tree.nearest_k(query, 3).back().first, static_cast<int>(points.rows() - 1), index}) {
      const auto [hinted_index, hinted_squared] = tree.nearest(query, hint);
      EXPECT_NEAR(hinted_squared, best, 1e-12) << "from hint " << hint;
      EXPECT_NEAR(squared_distance(points, hinted_index, query), best, 1e-12) << "from hint " << hint;
    }
    EXPECT_NEAR(squared_distance(points, all_index[static_cast<std::size_t>(q)], query), best, 1e-12);

    // The k nearest: distinct rows, nearest first, and their distances the k smallest of the scan.
    const int k = 5;
    const auto found_k = tree.nearest_k(query, k);
    const auto expected_k = std::min<Eigen::Index>(k, points.rows());
    ASSERT_EQ(static_cast<Eigen::Index>(found_k.size()), expected_k);
    const Eigen::VectorXd scan = (points.rowwise() - query.transpose()).rowwise().squaredNorm();
    std::vector<double> all(scan.data(), scan.data() + scan.size());
    std::sort(all.begin(), all.end());
    std::set<int> distinct;
    for (std::size_t i = 0; i < found_k.size(); ++i) {
      distinct.insert(found_k[i].first);
      EXPECT_NEAR(found_k[i].second, all[i], 1e-12) << "neighbour " << i;
      EXPECT_NEAR(squared_distance(points, found_k[i].first, query), all[i], 1e-12) << "neighbour " << i;
    }
    EXPECT_EQ(distinct.size(), found_k.size()) << "a row returned twice";

    // The radius search: exactly the rows inside the ball (rows on its surface may go either way).
    std::set<int> on_boundary;
    const std::set<int> inside = brute_within(points, query, radius, 1e-9, &on_boundary);
    std::vector<std::pair<int, double>> found;
    tree.radius(query, radius, found);
    std::set<int> returned;
    for (const auto& [row, squared_found] : found) {
      EXPECT_TRUE(returned.insert(row).second) << "row " << row << " returned twice";
      EXPECT_NEAR(squared_found, squared_distance(points, row, query), 1e-12);
      if (!on_boundary.count(row)) EXPECT_TRUE(inside.count(row)) << "row " << row << " is outside the ball";
    }
    for (const int row : inside) EXPECT_TRUE(returned.count(row)) << "row " << row << " inside was missed";
  }
}

TEST(KdTree, MatchesBruteForceOnARandomCloud) {
  const Points points = random_points(3000, 7);
  // Queries inside the cloud, on its points themselves, and far outside it.
  Points queries(230, 3);
  queries.topRows(100) = random_points(100, 8);
  queries.middleRows(100, 100) = points.topRows(100);
  queries.bottomRows(30) = random_points(30, 9, 5.0);
  expect_matches_brute_force(points, queries, 0.2);
}

TEST(KdTree, MatchesBruteForceOnDuplicatedPoints) {
  // Every point four times over, and a block of 40 copies of one point (more than a leaf holds).
  const Points distinct = random_points(200, 11);
  Points points(distinct.rows() * 4 + 40, 3);
  for (int copy = 0; copy < 4; ++copy) points.middleRows(copy * distinct.rows(), distinct.rows()) = distinct;
  points.bottomRows(40).rowwise() = Eigen::RowVector3d(0.25, -0.5, 0.125);
  Points queries(60, 3);
  queries.topRows(50) = random_points(50, 12);
  queries.bottomRows(10).rowwise() = Eigen::RowVector3d(0.25, -0.5, 0.125);
  expect_matches_brute_force(points, queries, 0.3);

  // All 40 copies lie within any radius of their own position.
  const KdTree tree(points);
  std::vector<std::pair<int, double>> found;
  tree.radius(Eigen::Vector3d(0.25, -0.5, 0.125), 1e-6, found);
  EXPECT_GE(found.size(), 40u);
}

TEST(KdTree, MatchesBruteForceOnDegenerateSets) {
  const Points queries = random_points(40, 21);
  {
    SCOPED_TRACE("all points coincide");
    Points same(50, 3);
    same.rowwise() = Eigen::RowVector3d(0.1, 0.2, 0.3);
    expect_matches_brute_force(same, queries, 0.5);
  }
  {
    SCOPED_TRACE("points on a line");
    Points line(500, 3);
    for (Eigen::Index i = 0; i < line.rows(); ++i)
      line.row(i) = (i / 250.0 - 1.0) * Eigen::RowVector3d(1, 2, -1);
    expect_matches_brute_force(line, queries, 0.3);
  }
  {
    SCOPED_TRACE("points on a plane (z = 0)");
    Points plane = random_points(800, 22);
    plane.col(2).setZero();
    expect_matches_brute_force(plane, queries, 0.3);
  }
  {
    SCOPED_TRACE("one point");
    expect_matches_brute_force(Points(Eigen::RowVector3d(1, -1, 0.5)), queries, 2.0);
  }
}

TEST(KdTree, KeepsItsAnswersWhenMovedAndRefusesAnEmptySet) {
  const Points points = random_points(500, 31);
  KdTree moved_into = KdTree(Points(random_points(10, 32)));
  {
    KdTree original(points);
    moved_into = std::move(original);  // the tree must now read the moved-to copy of the points
  }
  const Eigen::Vector3d query(0.3, 0.1, -0.2);
  EXPECT_NEAR(moved_into.nearest(query).second, brute_nearest_squared(points, query), 1e-12);
  EXPECT_THROW(KdTree(Points(0, 3)), InputError);
}

}  // namespace
}  // namespace partreg::core
