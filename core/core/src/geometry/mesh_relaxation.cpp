#include "mesh_relaxation.hpp"

#include <Eigen/Geometry>
#include <Eigen/Sparse>
#include <algorithm>
#include <map>
#include <set>
#include <tuple>

namespace partreg::core::detail {
namespace {

// Vertices at one position are one point of the surface (mesh files split them at seams of normals or
// texture): each vertex's representative, the first vertex at its position.
std::vector<int> welded(const Points& reference) {
  std::map<std::tuple<double, double, double>, int> first;
  std::vector<int> representative(static_cast<std::size_t>(reference.rows()));
  for (Eigen::Index v = 0; v < reference.rows(); ++v) {
    const auto key = std::make_tuple(reference(v, 0), reference(v, 1), reference(v, 2));
    representative[static_cast<std::size_t>(v)] = first.emplace(key, static_cast<int>(v)).first->second;
  }
  return representative;
}

// The representatives' neighbours over the faces' edges, each with its cotangent weight on the reference
// (linear precision: a displacement varying linearly along the surface is its own harmonic fill, so the fill
// does not slide vertices along it as uniform weights do on an irregular mesh). Weights are kept above a
// small positive floor: an obtuse pair of angles would make them negative.
using Neighbours = std::vector<std::map<int, double>>;
Neighbours neighbours(const Faces& faces, const Points& reference, const std::vector<int>& representative) {
  constexpr double kLeastWeight = 1e-2;
  Neighbours adjacent(representative.size());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int i = faces(f, e), j = faces(f, (e + 1) % 3), k = faces(f, (e + 2) % 3);
      const int a = representative[static_cast<std::size_t>(i)], b = representative[static_cast<std::size_t>(j)];
      if (a == b) continue;
      const Eigen::RowVector3d u = reference.row(i) - reference.row(k), v = reference.row(j) - reference.row(k);
      const double sine = u.cross(v).norm();
      const double cotangent = sine > 0.0 ? 0.5 * u.dot(v) / sine : 0.0;
      adjacent[static_cast<std::size_t>(a)][b] += cotangent;
      adjacent[static_cast<std::size_t>(b)][a] += cotangent;
    }
  for (auto& around : adjacent)
    for (auto& [neighbour, weight] : around) weight = std::max(weight, kLeastWeight);
  return adjacent;
}

// The region's displacement smoothed: each region vertex pulled to the weighted mean of its neighbours' and,
// by `screen`, to its own (0: the harmonic fill; 1: about as firmly as to its neighbours), vertices outside the
// region fixed. A tiny least pull keeps a region with no fixed neighbour (a loose part) solvable.
Eigen::MatrixXd smoothed(const Neighbours& adjacent, const std::vector<int>& region,
                         const Eigen::MatrixXd& displacement, double screen) {
  const double own_pull = std::max(screen, 1e-6);
  Eigen::MatrixXd out = displacement;
  std::map<int, int> unknown;
  for (int v : region) unknown.emplace(v, static_cast<int>(unknown.size()));
  const auto n = static_cast<Eigen::Index>(unknown.size());
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
  for (const auto& [v, row] : unknown) {
    double total = own_pull;
    rhs.row(row) = own_pull * displacement.row(v);
    for (const auto& [w, weight] : adjacent[static_cast<std::size_t>(v)]) {
      total += weight;
      const auto inside = unknown.find(w);
      if (inside != unknown.end())
        entries.emplace_back(row, inside->second, -weight);
      else
        rhs.row(row) += weight * displacement.row(w);
    }
    entries.emplace_back(row, row, total);
  }
  Eigen::SparseMatrix<double> system(n, n);
  system.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(system);
  if (solver.info() != Eigen::Success) return out;  // symmetric and diagonally dominant: not expected
  const Eigen::MatrixXd solved = solver.solve(rhs);
  for (const auto& [v, row] : unknown) out.row(v) = solved.row(row);
  return out;
}

// The fault faces' vertices (representatives) and `rings` rings of neighbours around them.
std::vector<int> grow(const Neighbours& adjacent, std::set<int> region, int rings) {
  for (int ring = 0; ring < rings; ++ring) {
    std::set<int> next = region;
    for (int v : region)
      for (const auto& [neighbour, weight] : adjacent[static_cast<std::size_t>(v)]) next.insert(neighbour);
    region = std::move(next);
  }
  return {region.begin(), region.end()};
}

}  // namespace

std::vector<int> faulty_faces(const Faces& faces, const Points& reference, const Points& deformed,
                              const MeshFaults& faults) {
  std::vector<int> faulty;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::RowVector3d a = reference.row(faces(f, 0)), b = reference.row(faces(f, 1)),
                             c = reference.row(faces(f, 2));
    const Eigen::RowVector3d p = deformed.row(faces(f, 0)), q = deformed.row(faces(f, 1)),
                             r = deformed.row(faces(f, 2));
    const bool turned = (b - a).cross(c - a).dot((q - p).cross(r - p)) < 0.0;
    const auto stretched = [&](const Eigen::RowVector3d& from, const Eigen::RowVector3d& to, double length) {
      return length > faults.stretch_limit * (to - from).norm();
    };
    if (turned || stretched(a, b, (q - p).norm()) || stretched(b, c, (r - q).norm()) ||
        stretched(c, a, (p - r).norm()))
      faulty.push_back(static_cast<int>(f));
  }
  return faulty;
}

Points relax_faults(const Faces& faces, const Points& reference, const Points& deformed, const MeshFaults& faults) {
  std::vector<int> faulty = faulty_faces(faces, reference, deformed, faults);
  if (faulty.empty()) return deformed;
  const std::vector<int> representative = welded(reference);
  const Neighbours adjacent = neighbours(faces, reference, representative);
  const Eigen::MatrixXd displacement = deformed - reference;  // rows of representatives are read
  const double largest_shift =
      faults.largest_shift * (reference.colwise().maxCoeff() - reference.colwise().minCoeff()).norm();
  std::set<int> region;
  Points best = deformed;
  std::size_t fewest = faulty.size();
  double screen = faults.first_screen;
  for (int round = 0; round < faults.rounds && !faulty.empty(); ++round, screen *= faults.screen_step) {
    for (int f : faulty)
      for (int e = 0; e < 3; ++e) region.insert(representative[static_cast<std::size_t>(faces(f, e))]);
    // Each round repairs the faults left and their rings with what it repaired before, smoothing more.
    const std::vector<int> repaired = grow(adjacent, region, faults.rings);
    region.insert(repaired.begin(), repaired.end());
    const Eigen::MatrixXd smooth = smoothed(adjacent, repaired, displacement, screen);
    Points relaxed(deformed.rows(), 3);
    for (Eigen::Index v = 0; v < relaxed.rows(); ++v)
      relaxed.row(v) = reference.row(v) + smooth.row(representative[static_cast<std::size_t>(v)]);
    // A repair that would move the surface away from what the fit found is not kept: the fold is real.
    if ((relaxed - deformed).rowwise().norm().maxCoeff() > largest_shift) break;
    faulty = faulty_faces(faces, reference, relaxed, faults);
    if (faulty.size() < fewest) fewest = faulty.size(), best = relaxed;
  }
  return best;
}

}  // namespace partreg::core::detail
