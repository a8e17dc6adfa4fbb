#pragma once
/// \file
/// A coarse stand-in for a dense mesh, drawn in interactive frames. On software GL a frame's cost grows with
/// the triangle count (about 0.25 ms per thousand triangles with llvmpipe on two cores), so a
/// 100,000-triangle mesh cannot follow a slider at 30 frames per second; its proxy can. The proxy clusters
/// the mesh's vertices on a grid once (vertex clustering, Rossignac and Borrel 1993) and keeps that grouping:
/// each frame a proxy vertex is the mean of its cluster's current vertices, so the proxy follows any
/// deformation of the mesh in one pass over its vertices.

#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::render {

class MeshProxy {
 public:
  MeshProxy() = default;
  /// Groups the vertices of `mesh` by the cells of the finest cubic grid over its bounding box whose proxy
  /// has at most `max_triangles` triangles (found by bisection on the grid's resolution). Faces whose corners
  /// fall into fewer than three clusters disappear, and faces over the same three clusters are drawn once.
  MeshProxy(const core::Mesh& mesh, int max_triangles);

  /// Proxy triangles over cluster indices.
  const core::Faces& faces() const { return faces_; }
  int cluster_count() const { return static_cast<int>(representative_.size()); }
  /// The number of vertices of the mesh it was built from.
  Eigen::Index vertex_count() const { return static_cast<Eigen::Index>(cluster_of_.size()); }
  /// For each cluster, one mesh vertex in it (whose colour the cluster takes).
  const std::vector<int>& representatives() const { return representative_; }
  /// The proxy of the mesh with these vertices (same count as the mesh it was built from): cluster means.
  core::Points vertices(const core::Points& mesh_vertices) const;

 private:
  std::vector<int> cluster_of_;       // per mesh vertex
  std::vector<int> representative_;   // per cluster
  std::vector<double> inverse_size_;  // per cluster: 1 / its vertex count
  core::Faces faces_;
};

}  // namespace partreg::render
