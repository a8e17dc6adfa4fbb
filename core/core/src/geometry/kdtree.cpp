#include "partreg/core/geometry/kdtree.hpp"

#include <algorithm>
#include <nanoflann.hpp>

#include "partreg/core/errors.hpp"
#include "partreg/core/parallel.hpp"

namespace partreg::core {
namespace {

// nanoflann's dataset adaptor over the tree's own row-major points.
struct PointsAdaptor {
  const Points* points;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(points->rows()); }
  double kdtree_get_pt(std::size_t index, std::size_t dim) const {
    return (*points)(static_cast<Eigen::Index>(index), static_cast<Eigen::Index>(dim));
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointsAdaptor>,
                                                 PointsAdaptor, 3, int>;

}  // namespace

struct KdTree::Index {
  PointsAdaptor adaptor;
  Tree tree;
  explicit Index(const Points* points)
      : adaptor{points}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(/*leaf_max_size=*/16)) {
    tree.buildIndex();
  }
};

KdTree::KdTree(Points points) : points_(std::move(points)) {
  if (points_.rows() == 0) throw InputError("cannot build a KD-tree over an empty point set");
  index_ = std::make_unique<Index>(&points_);
}

KdTree::~KdTree() = default;

// Moving an Eigen matrix keeps its heap buffer, so the adaptor only needs to be pointed at the new member.
KdTree::KdTree(KdTree&& other) noexcept : points_(std::move(other.points_)), index_(std::move(other.index_)) {
  if (index_) index_->adaptor.points = &points_;
}

KdTree& KdTree::operator=(KdTree&& other) noexcept {
  points_ = std::move(other.points_);
  index_ = std::move(other.index_);
  if (index_) index_->adaptor.points = &points_;
  return *this;
}

std::pair<int, double> KdTree::nearest(const Eigen::Vector3d& query) const {
  int index = 0;
  double squared = 0.0;
  nanoflann::KNNResultSet<double, int> result(1);
  result.init(&index, &squared);
  index_->tree.findNeighbors(result, query.data(), nanoflann::SearchParams());
  return {index, squared};
}

namespace {

// A nanoflann result set for one nearest point that starts with a known point and its distance as the
// bound, so the search visits only the cells that could hold a closer one.
struct CloserThan {
  int index;
  double squared;
  std::size_t size() const { return 1; }
  bool full() const { return true; }
  double worstDist() const { return squared; }
  bool addPoint(double distance, int row) {
    if (distance < squared) squared = distance, index = row;
    return true;
  }
};

}  // namespace

std::pair<int, double> KdTree::nearest(const Eigen::Vector3d& query, int hint) const {
  CloserThan result{hint, (points_.row(hint).transpose() - query).squaredNorm()};
  index_->tree.findNeighbors(result, query.data(), nanoflann::SearchParams());
  return {result.index, result.squared};
}

void KdTree::nearest_all(const Points& queries, std::vector<int>& index,
                         Eigen::VectorXd& squared_distance) const {
  index.resize(static_cast<std::size_t>(queries.rows()));
  squared_distance.resize(queries.rows());
  parallel_for(queries.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for (Eigen::Index i = begin; i < end; ++i) {
      const auto [nearest_index, squared] = nearest(queries.row(i).transpose());
      index[static_cast<std::size_t>(i)] = nearest_index;
      squared_distance[i] = squared;
    }
  });
}

std::vector<std::pair<int, double>> KdTree::nearest_k(const Eigen::Vector3d& query, int k) const {
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(std::max(k, 0)),
                                                  static_cast<std::size_t>(points_.rows()));
  std::vector<int> index(count);
  std::vector<double> squared(count);
  nanoflann::KNNResultSet<double, int> result(count);
  result.init(index.data(), squared.data());
  if (count > 0) index_->tree.findNeighbors(result, query.data(), nanoflann::SearchParams());
  std::vector<std::pair<int, double>> found(count);
  for (std::size_t i = 0; i < count; ++i) found[i] = {index[i], squared[i]};
  return found;
}

void KdTree::radius(const Eigen::Vector3d& query, double radius,
                    std::vector<std::pair<int, double>>& found) const {
  found.clear();
  nanoflann::SearchParams params;
  params.sorted = false;
  index_->tree.radiusSearch(query.data(), radius * radius, found, params);
}

}  // namespace partreg::core
