#include "partreg/render/mesh_proxy.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "partreg/render/scene.hpp"

namespace partreg::render {
namespace {

// Vertex clusters and proxy faces for one grid resolution (cells along the box's longest side).
struct Clustering {
  std::vector<int> cluster_of;
  std::vector<int> representative;
  core::Faces faces;
};

// Which of the six axis directions a vertex's normal is closest to: clusters split by it, so that the two
// sides of a thin wall or a handle (close in space, facing apart) do not collapse into one.
std::vector<int> normal_bins(const core::Mesh& mesh) {
  const core::Points normals =
      mesh.normals.rows() == mesh.vertices.rows() ? mesh.normals : vertex_normals(mesh);
  std::vector<int> bins(static_cast<std::size_t>(normals.rows()));
  for (Eigen::Index v = 0; v < normals.rows(); ++v) {
    Eigen::Index axis = 0;
    normals.row(v).cwiseAbs().maxCoeff(&axis);
    bins[static_cast<std::size_t>(v)] = 2 * static_cast<int>(axis) + (normals(v, axis) < 0.0 ? 1 : 0);
  }
  return bins;
}

Clustering cluster(const core::Mesh& mesh, const std::vector<int>& bins, int resolution) {
  const Eigen::RowVector3d low = mesh.vertices.colwise().minCoeff();
  const double extent = (mesh.vertices.colwise().maxCoeff() - low).maxCoeff();
  const double cell = extent > 0.0 ? extent / resolution : 1.0;
  Clustering result;
  result.cluster_of.resize(static_cast<std::size_t>(mesh.vertices.rows()));
  std::unordered_map<std::int64_t, int> cluster_of_cell;
  cluster_of_cell.reserve(static_cast<std::size_t>(mesh.vertices.rows()));
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    std::int64_t key = bins[static_cast<std::size_t>(v)];
    for (int c = 0; c < 3; ++c)
      key = key * (resolution + 2) +
            std::clamp(static_cast<std::int64_t>((mesh.vertices(v, c) - low[c]) / cell), std::int64_t{0},
                       static_cast<std::int64_t>(resolution));
    const auto [found, inserted] =
        cluster_of_cell.try_emplace(key, static_cast<int>(result.representative.size()));
    if (inserted) result.representative.push_back(static_cast<int>(v));
    result.cluster_of[static_cast<std::size_t>(v)] = found->second;
  }
  std::vector<std::array<int, 3>> faces;
  std::unordered_set<std::int64_t> seen;
  seen.reserve(static_cast<std::size_t>(mesh.faces.rows()));
  const auto clusters = static_cast<std::int64_t>(result.representative.size());
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    std::array<int, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = result.cluster_of[static_cast<std::size_t>(mesh.faces(f, k))];
    if (corners[0] == corners[1] || corners[1] == corners[2] || corners[0] == corners[2]) continue;
    std::array<int, 3> sorted = corners;
    std::sort(sorted.begin(), sorted.end());
    if (seen.insert((sorted[0] * clusters + sorted[1]) * clusters + sorted[2]).second)
      faces.push_back(corners);
  }
  result.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) result.faces(static_cast<Eigen::Index>(f), k) = faces[f][k];
  return result;
}

}  // namespace

MeshProxy::MeshProxy(const core::Mesh& mesh, int max_triangles) {
  if (mesh.vertices.rows() == 0) return;
  // A surface's proxy has about resolution^2 triangles: one probe estimates the resolution, then steps of
  // 10% find the finest within the budget (two to four clusterings instead of a dozen for a bisection).
  constexpr int kProbe = 32;
  const std::vector<int> bins = normal_bins(mesh);
  Clustering best = cluster(mesh, bins, kProbe);
  const double ratio = static_cast<double>(max_triangles) / std::max<Eigen::Index>(best.faces.rows(), 1);
  int resolution = std::clamp(static_cast<int>(kProbe * std::sqrt(ratio)), 1, 4096);
  Clustering trial = cluster(mesh, bins, resolution);
  while (trial.faces.rows() > max_triangles && resolution > 1) {
    resolution = std::min(resolution - 1, static_cast<int>(resolution * 0.9));
    trial = cluster(mesh, bins, resolution);
  }
  if (trial.faces.rows() <= max_triangles) best = std::move(trial);
  for (int finer = resolution * 11 / 10 + 1; finer <= 4096; finer = finer * 11 / 10 + 1) {
    Clustering next = cluster(mesh, bins, finer);
    if (next.faces.rows() > max_triangles) break;
    best = std::move(next);
  }
  cluster_of_ = std::move(best.cluster_of);
  representative_ = std::move(best.representative);
  faces_ = std::move(best.faces);
  std::vector<int> sizes(representative_.size(), 0);
  for (const int c : cluster_of_) ++sizes[static_cast<std::size_t>(c)];
  inverse_size_.resize(sizes.size());
  for (std::size_t c = 0; c < sizes.size(); ++c) inverse_size_[c] = 1.0 / sizes[c];
}

core::Points MeshProxy::vertices(const core::Points& mesh_vertices) const {
  core::Points means = core::Points::Zero(static_cast<Eigen::Index>(representative_.size()), 3);
  for (std::size_t v = 0; v < cluster_of_.size(); ++v)
    means.row(cluster_of_[v]) += mesh_vertices.row(static_cast<Eigen::Index>(v));
  for (std::size_t c = 0; c < inverse_size_.size(); ++c)
    means.row(static_cast<Eigen::Index>(c)) *= inverse_size_[c];
  return means;
}

}  // namespace partreg::render
