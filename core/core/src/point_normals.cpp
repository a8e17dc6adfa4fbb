#include "point_normals.hpp"

#include <Eigen/Eigenvalues>

#include "partreg/core/kdtree.hpp"

namespace partreg::core::detail {
namespace {

// The scatter matrix (sum of outer products about their mean) of the rows of `points` listed in `neighbours`
// (index, squared distance pairs, as KdTree returns them), and their mean in `mean`.
Eigen::Matrix3d neighbourhood_scatter(const Points& points, const std::vector<std::pair<int, double>>& neighbours,
                                      Eigen::Vector3d& mean) {
  mean = Eigen::Vector3d::Zero();
  for (const auto& [j, d2] : neighbours) mean += points.row(j).transpose();
  mean /= static_cast<double>(std::max<std::size_t>(neighbours.size(), 1));
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& [j, d2] : neighbours)
    scatter += (points.row(j).transpose() - mean) * (points.row(j) - mean.transpose());
  return scatter;
}

}  // namespace

Points outward_normals(const Points& points, double radius) {
  const KdTree tree(points);
  const Eigen::RowVector3d centre = points.colwise().mean();
  Points normals(points.rows(), 3);
  std::vector<std::pair<int, double>> near;
  for (Eigen::Index m = 0; m < points.rows(); ++m) {
    tree.radius(points.row(m).transpose(), radius, near);
    Eigen::Vector3d mean;
    const Eigen::Matrix3d covariance = neighbourhood_scatter(points, near, mean);
    Eigen::Vector3d normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
    if (normal.dot((points.row(m) - centre).transpose()) < 0.0) normal = -normal;
    normals.row(m) = normal.transpose();
  }
  return normals;
}

Points canonical_normals(const Points& points) { return outward_normals(points, 0.05); }

}  // namespace partreg::core::detail
