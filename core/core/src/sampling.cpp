#include "partreg/core/sampling.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <unordered_map>

#include "partreg/core/errors.hpp"

namespace partreg::core {

Cloud sample_surface(const Mesh& mesh, std::size_t count, std::uint64_t seed) {
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
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(count); ++i) {
    const Eigen::Index f = pick_face(generator);
    // sqrt on the first coordinate makes the barycentric point uniform over the triangle's area.
    const double r1 = std::sqrt(uniform(generator)), r2 = uniform(generator);
    cloud.points.row(i) = (1.0 - r1) * mesh.vertices.row(mesh.faces(f, 0)) +
                          r1 * (1.0 - r2) * mesh.vertices.row(mesh.faces(f, 1)) +
                          r1 * r2 * mesh.vertices.row(mesh.faces(f, 2));
    cloud.normals.row(i) = normals.row(f);
  }
  return cloud;
}

std::vector<int> farthest_point_indices(const Points& points, std::size_t count, int first) {
  if (static_cast<Eigen::Index>(count) > points.rows())
    throw InputError("asked for " + std::to_string(count) + " points but the set has only " +
                     std::to_string(points.rows()));
  if (count == 0) return {};
  if (first < 0 || first >= points.rows()) throw UsageError("farthest-point sampling: bad first index");
  // One pass per chosen point over separate coordinate arrays: update each distance to the chosen set and
  // find the farthest in the same loop (the compiler vectorises it; no temporaries per step).
  const Eigen::Index n = points.rows();
  const Eigen::VectorXd xs = points.col(0), ys = points.col(1), zs = points.col(2);
  const double *x = xs.data(), *y = ys.data(), *z = zs.data();
  std::vector<double> distance(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
  // A chosen row's distance is -1, below every distance left, so no row is chosen twice even once every
  // distinct position is taken and the rest are duplicates at distance 0.
  distance[static_cast<std::size_t>(first)] = -1.0;
  std::vector<int> chosen{first};
  chosen.reserve(count);
  Eigen::Index next = first;
  while (chosen.size() < count) {
    const double cx = x[next], cy = y[next], cz = z[next];
    double farthest = -2.0;
    Eigen::Index farthest_index = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double dx = x[i] - cx, dy = y[i] - cy, dz = z[i] - cz;
      const double d = std::min(distance[static_cast<std::size_t>(i)], dx * dx + dy * dy + dz * dz);
      distance[static_cast<std::size_t>(i)] = d;
      if (d > farthest) {
        farthest = d;
        farthest_index = i;
      }
    }
    next = farthest_index;
    distance[static_cast<std::size_t>(next)] = -1.0;
    chosen.push_back(static_cast<int>(next));
  }
  return chosen;
}

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
  // First pass: each voxel's centroid; second: the point nearest to it.
  std::unordered_map<std::uint64_t, int> voxel_of_key;
  voxel_of_key.reserve(static_cast<std::size_t>(points.rows() / 4 + 1));
  std::vector<int> voxel(static_cast<std::size_t>(points.rows()));
  std::vector<Eigen::RowVector4d> sums;  // x y z count
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::RowVector3d cell = ((points.row(i) - lower) / voxel_size).array().floor();
    const auto key = static_cast<std::uint64_t>(cell[0] + cells[0] * (cell[1] + cells[1] * cell[2]));
    const auto [found, inserted] = voxel_of_key.try_emplace(key, static_cast<int>(sums.size()));
    if (inserted) sums.emplace_back(Eigen::RowVector4d::Zero());
    sums[static_cast<std::size_t>(found->second)] += Eigen::RowVector4d(points(i, 0), points(i, 1), points(i, 2), 1.0);
    voxel[static_cast<std::size_t>(i)] = found->second;
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
  std::sort(best.begin(), best.end());  // the input's order: deterministic, whatever the hashing
  return best;
}

std::vector<int> subsample_indices(const Points& points, std::size_t count, double voxel_size) {
  if (static_cast<Eigen::Index>(count) >= points.rows()) {
    std::vector<int> all(static_cast<std::size_t>(points.rows()));
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    return all;
  }
  if (voxel_size <= 0.0) return farthest_point_indices(points, count);
  const std::vector<int> kept = voxel_representatives(points, voxel_size);
  if (kept.size() <= count) return kept;
  std::vector<int> chosen = farthest_point_indices(select_rows(points, kept), count);
  for (int& row : chosen) row = kept[static_cast<std::size_t>(row)];
  return chosen;
}

Points select_rows(const Points& points, const std::vector<int>& rows) {
  Points selected(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    selected.row(static_cast<Eigen::Index>(i)) = points.row(rows[i]);
  return selected;
}

}  // namespace partreg::core
