#include "partreg/core/geometry/sampling.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <random>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/parallel.hpp"

namespace partreg::core {

Cloud sample_surface(const Mesh& mesh, std::size_t count, std::uint64_t seed,
                     Eigen::VectorXi* face_of_point) {
  if (count == 0) throw UsageError("asked for 0 surface samples");
  if (mesh.faces.rows() == 0) throw InputError("cannot sample a mesh with no faces");
  std::vector<double> areas(static_cast<std::size_t>(mesh.faces.rows()));
  Points normals(mesh.faces.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    areas[static_cast<std::size_t>(f)] = 0.5 * cross.norm();
    normals.row(f) = cross.norm() > 0.0 ? Eigen::Vector3d(cross.normalized()) : Eigen::Vector3d::Zero();
  }
  double total = 0.0;
  for (double area : areas) total += area;
  if (!(total > 0.0) || !std::isfinite(total)) throw InputError("cannot sample a mesh with no surface area");

  std::mt19937_64 generator(seed);
  std::discrete_distribution<Eigen::Index> pick_face(areas.begin(), areas.end());
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Cloud cloud;
  cloud.points.resize(static_cast<Eigen::Index>(count), 3);
  cloud.normals.resize(static_cast<Eigen::Index>(count), 3);
  if (face_of_point) face_of_point->resize(static_cast<Eigen::Index>(count));
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(count); ++i) {
    const Eigen::Index f = pick_face(generator);
    // sqrt on the first coordinate makes the barycentric point uniform over the triangle's area.
    const double r1 = std::sqrt(uniform(generator)), r2 = uniform(generator);
    cloud.points.row(i) = (1.0 - r1) * mesh.vertices.row(mesh.faces(f, 0)) +
                          r1 * (1.0 - r2) * mesh.vertices.row(mesh.faces(f, 1)) +
                          r1 * r2 * mesh.vertices.row(mesh.faces(f, 2));
    cloud.normals.row(i) = normals.row(f);
    if (face_of_point) (*face_of_point)[i] = static_cast<int>(f);
  }
  return cloud;
}

std::vector<int> farthest_point_indices(const Points& points, std::size_t count, int first) {
  if (static_cast<Eigen::Index>(count) > points.rows())
    throw InputError("asked for " + std::to_string(count) + " points but the set has only " +
                     std::to_string(points.rows()));
  if (count == 0) return {};
  if (first < 0 || first >= points.rows()) throw UsageError("farthest-point sampling: bad first index");
  if (!points.allFinite()) throw InputError("farthest-point sampling: a point is not finite (NaN or infinite)");
  // Choosing a point can only lower the distance of points closer to it than the farthest distance left
  // (the chosen point's own), so each step updates just the points within that radius (a KD-tree query)
  // instead of all of them, and a max-heap keeps the farthest point (stale entries are skipped when they
  // surface). Ties go to the lowest row, so the result is that of the plain O(N count) loop.
  const auto n = static_cast<std::size_t>(points.rows());
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  // A chosen row's distance is -1, below every distance left, so no row is chosen twice even once every
  // distinct position is taken and the rest are duplicates at distance 0.
  distance[static_cast<std::size_t>(first)] = -1.0;
  using Entry = std::pair<double, int>;  // distance, row
  const auto before = [](const Entry& a, const Entry& b) {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
  };
  std::priority_queue<Entry, std::vector<Entry>, decltype(before)> farthest(before);
  const KdTree tree(points);
  std::vector<std::pair<int, double>> near;
  std::vector<int> chosen{first};
  chosen.reserve(count);
  double reach = std::numeric_limits<double>::infinity();  // squared distance of the point just chosen
  while (chosen.size() < count) {
    const Eigen::RowVector3d centre = points.row(chosen.back());
    const auto update = [&](int row) {
      const double d = (points.row(row) - centre).squaredNorm();
      if (d < distance[static_cast<std::size_t>(row)]) {
        distance[static_cast<std::size_t>(row)] = d;
        farthest.push({d, row});
      }
    };
    if (std::isfinite(reach)) {
      tree.radius(centre.transpose(), std::sqrt(reach) * (1.0 + 1e-9) + 1e-300, near);
      for (const auto& [row, squared] : near) update(row);
    } else {
      for (std::size_t row = 0; row < n; ++row) update(static_cast<int>(row));
    }
    while (farthest.top().first != distance[static_cast<std::size_t>(farthest.top().second)]) farthest.pop();
    const auto [d, row] = farthest.top();
    farthest.pop();
    reach = d;
    distance[static_cast<std::size_t>(row)] = -1.0;
    chosen.push_back(row);
  }
  return chosen;
}

namespace {

// Voxel key -> voxel number, open addressing with linear probing in a power-of-two table kept at most half full:
// the standard map's node per voxel made it the slowest part of the pass over a million points.
class VoxelNumbers {
 public:
  explicit VoxelNumbers(std::size_t expected) { rehash(std::max<std::size_t>(64, 2 * expected)); }

  // The number of the voxel `key`; a new voxel gets the next number.
  int number(std::uint64_t key) {
    if (2 * (count_ + 1) > keys_.size()) rehash(2 * keys_.size());
    std::size_t slot = slot_of(key);
    while (keys_[slot] != kEmpty && keys_[slot] != key) slot = (slot + 1) & mask_;
    if (keys_[slot] == kEmpty) {
      keys_[slot] = key;
      numbers_[slot] = static_cast<int>(count_++);
    }
    return numbers_[slot];
  }
  std::size_t size() const { return count_; }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // never a key: keys stay below 9e18
  std::size_t slot_of(std::uint64_t key) const { return (key * 0x9E3779B97F4A7C15ull >> 17) & mask_; }
  void rehash(std::size_t wanted) {
    std::size_t capacity = 64;
    while (capacity < wanted) capacity *= 2;
    std::vector<std::uint64_t> keys(capacity, kEmpty);
    std::vector<int> numbers(capacity, -1);
    keys.swap(keys_);
    numbers.swap(numbers_);
    mask_ = capacity - 1;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (keys[i] == kEmpty) continue;
      std::size_t slot = slot_of(keys[i]);
      while (keys_[slot] != kEmpty) slot = (slot + 1) & mask_;
      keys_[slot] = keys[i];
      numbers_[slot] = numbers[i];
    }
  }
  std::vector<std::uint64_t> keys_;
  std::vector<int> numbers_;
  std::size_t mask_ = 0, count_ = 0;
};

}  // namespace

std::vector<int> voxel_representatives(const Points& points, double voxel_size) {
  if (!(voxel_size > 0.0) || !std::isfinite(voxel_size))
    throw UsageError("the voxel size must be positive, got " + std::to_string(voxel_size));
  const Eigen::RowVector3d lower = points.colwise().minCoeff();
  const Eigen::RowVector3d cells = ((points.colwise().maxCoeff() - lower) / voxel_size).array().floor() + 1.0;
  if (!(cells.prod() < 9e18)) {  // a voxel so small against the set that nothing would merge
    std::vector<int> all(static_cast<std::size_t>(points.rows()));
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    return all;
  }
  // The keys in parallel (independent per point), then the voxels numbered in the input's order.
  std::vector<std::uint64_t> keys(static_cast<std::size_t>(points.rows()));
  parallel_for(points.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for (Eigen::Index i = begin; i < end; ++i) {
      const Eigen::RowVector3d cell = ((points.row(i) - lower) / voxel_size).array().floor();
      keys[static_cast<std::size_t>(i)] = static_cast<std::uint64_t>(cell[0] + cells[0] * (cell[1] + cells[1] * cell[2]));
    }
  }, 0, 1 << 16);
  // First pass: each voxel's centroid; second: the point nearest to it.
  VoxelNumbers numbers(static_cast<std::size_t>(points.rows() / 8 + 1));
  std::vector<int> voxel(static_cast<std::size_t>(points.rows()));
  std::vector<Eigen::RowVector4d> sums;  // x y z count
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const int v = numbers.number(keys[static_cast<std::size_t>(i)]);
    if (static_cast<std::size_t>(v) == sums.size()) sums.emplace_back(Eigen::RowVector4d::Zero());
    sums[static_cast<std::size_t>(v)] += Eigen::RowVector4d(points(i, 0), points(i, 1), points(i, 2), 1.0);
    voxel[static_cast<std::size_t>(i)] = v;
  }
  std::vector<int> best(sums.size(), -1);
  std::vector<double> best_distance(sums.size(), std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const auto v = static_cast<std::size_t>(voxel[static_cast<std::size_t>(i)]);
    const double d = (points.row(i) - sums[v].head<3>() / sums[v][3]).squaredNorm();
    if (d < best_distance[v]) {
      best_distance[v] = d;
      best[v] = static_cast<int>(i);
    }
  }
  std::sort(best.begin(), best.end());  // the input's order
  return best;
}

namespace {

std::vector<int> all_rows(const Points& points) {
  std::vector<int> all(static_cast<std::size_t>(points.rows()));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return all;
}

}  // namespace

std::vector<int> subsample_indices(const Points& points, std::size_t count, double voxel_size) {
  if (static_cast<Eigen::Index>(count) >= points.rows()) return all_rows(points);
  if (voxel_size <= 0.0) return farthest_point_indices(points, count);
  const std::vector<int> kept = voxel_representatives(points, voxel_size);
  if (kept.size() <= count) return kept;
  std::vector<int> chosen = farthest_point_indices(select_rows(points, kept), count);
  for (int& row : chosen) row = kept[static_cast<std::size_t>(row)];
  return chosen;
}

std::vector<int> rows_with_neighbours(const Points& points, int neighbours, double limit) {
  std::vector<int> all = all_rows(points);
  if (!(limit > 0.0) || neighbours < 1 || points.rows() <= neighbours + 1) return all;
  const KdTree tree(points);
  // Squared distance to the `neighbours`-th nearest other row (the row itself comes first, at 0).
  std::vector<double> reach(all.size());
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    reach[static_cast<std::size_t>(i)] = tree.nearest_k(points.row(i).transpose(), neighbours + 1).back().second;
  std::vector<double> sorted = reach;
  const auto middle = sorted.begin() + static_cast<long>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  if (!(*middle > 0.0)) return all;  // mostly repeated points: no spacing to judge by
  const double squared_limit = limit * limit * *middle;
  std::vector<int> kept;
  for (int row : all)
    if (reach[static_cast<std::size_t>(row)] <= squared_limit) kept.push_back(row);
  return kept;
}

std::vector<int> rows_with(const Eigen::VectorXi& part_of_row, int part) {
  std::vector<int> rows;
  for (Eigen::Index i = 0; i < part_of_row.size(); ++i)
    if (part_of_row[i] == part) rows.push_back(static_cast<int>(i));
  return rows;
}

Points select_rows(const Points& points, const std::vector<int>& rows) {
  Points selected(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    selected.row(static_cast<Eigen::Index>(i)) = points.row(rows[i]);
  return selected;
}

}  // namespace partreg::core
