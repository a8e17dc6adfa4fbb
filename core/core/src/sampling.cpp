#include "partreg/core/sampling.hpp"

#include <Eigen/Geometry>
#include <random>

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
  std::vector<int> chosen{first};
  chosen.reserve(count);
  Eigen::VectorXd distance = (points.rowwise() - points.row(first)).rowwise().squaredNorm();
  while (chosen.size() < count) {
    Eigen::Index next = 0;
    distance.maxCoeff(&next);
    chosen.push_back(static_cast<int>(next));
    distance = distance.cwiseMin((points.rowwise() - points.row(next)).rowwise().squaredNorm());
  }
  return chosen;
}

Points select_rows(const Points& points, const std::vector<int>& rows) {
  Points selected(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    selected.row(static_cast<Eigen::Index>(i)) = points.row(rows[i]);
  return selected;
}

}  // namespace partreg::core
