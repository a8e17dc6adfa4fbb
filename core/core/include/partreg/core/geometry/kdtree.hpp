#pragma once
/// \file
/// Nearest-neighbour search over a point set (nanoflann). Every closest-point query in partreg goes
/// through this type: CPD's truncated E-step, label propagation, registration correspondences, metrics.

#include <memory>
#include <utility>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::core {

/// A static 3D KD-tree. It keeps its own copy of the points, so the source may go away.
class KdTree {
 public:
  explicit KdTree(Points points);
  ~KdTree();
  KdTree(KdTree&&) noexcept;
  KdTree& operator=(KdTree&&) noexcept;

  /// Index of the nearest point and its squared distance. The tree must not be empty.
  std::pair<int, double> nearest(const Eigen::Vector3d& query) const;
  /// The same, searching only closer than the point `hint` (an earlier answer for a query that has moved a
  /// little): the tree prunes all but a small neighbourhood, and the answer is still the nearest point (the
  /// hint itself when none is closer). `hint` must be a row of the tree.
  std::pair<int, double> nearest(const Eigen::Vector3d& query, int hint) const;
  /// Nearest point of every row of `queries` (threaded); fills index and squared distance per query.
  void nearest_all(const Points& queries, std::vector<int>& index, Eigen::VectorXd& squared_distance) const;
  /// The `k` nearest points (fewer if the tree holds fewer) as (index, squared distance), nearest first.
  std::vector<std::pair<int, double>> nearest_k(const Eigen::Vector3d& query, int k) const;
  /// Every point within `radius` of `query` as (index, squared distance), in no particular order.
  void radius(const Eigen::Vector3d& query, double radius, std::vector<std::pair<int, double>>& found) const;

  const Points& points() const { return points_; }
  Eigen::Index size() const { return points_.rows(); }

 private:
  struct Index;
  Points points_;
  std::unique_ptr<Index> index_;
};

}  // namespace partreg::core
